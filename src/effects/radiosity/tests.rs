//! Form factors against their closed forms, the matrix's invariants and the solvers against
//! exact solutions. The comparison with a path tracer is in tests/integration/radiosity_reference.rs.

use super::mesh::Patches;
use super::solve::{self, Rows};
use super::*;
use crate::geometry::subdivide::{divisions, lattice, sub_triangles};
use crate::lesson::settings::RadiositySettings;
use glam::Vec3;

/// Convex polygons (wound so their normal is the side that sends light), fanned and cut into
/// patches of at most `size`: positions, triangles, unit normals and the polygon of each patch.
struct Soup {
    positions: Vec<Vec3>,
    triangles: Vec<[u32; 3]>,
    normals: Vec<Vec3>,
    owner: Vec<usize>,
}

fn soup(polygons: &[Vec<Vec3>], size: f32) -> Soup {
    let mut s = Soup { positions: Vec::new(), triangles: Vec::new(), normals: Vec::new(), owner: Vec::new() };
    for (o, poly) in polygons.iter().enumerate() {
        for f in 1..poly.len() - 1 {
            let (a, b, c) = (poly[0], poly[f], poly[f + 1]);
            let n = (b - a).cross(c - a).normalize();
            let k = divisions(a, b, c, size);
            for t in sub_triangles(k) {
                let base = s.positions.len() as u32;
                s.positions.extend(t.map(|(i, j)| lattice(a, b, c, k, i, j)));
                s.triangles.push([base, base + 1, base + 2]);
                s.normals.push(n);
                s.owner.push(o);
            }
        }
    }
    s
}

fn patches(s: &Soup, e: impl Fn(usize) -> Vec3, rho: impl Fn(usize) -> Vec3) -> Patches {
    let n = s.triangles.len();
    Patches::from_triangles(
        &s.positions,
        &s.triangles,
        &s.normals,
        (0..n).map(|i| e(s.owner[i])).collect(),
        (0..n).map(|i| rho(s.owner[i])).collect(),
    )
}

fn settings(method: FormFactorMethod, hemicube_size: u32) -> RadiositySettings {
    RadiositySettings { form_factors: method, hemicube_size, ..RadiositySettings::default() }
}

fn matrix(s: &Soup, p: &Patches, method: FormFactorMethod, res: u32) -> Vec<Vec<(u32, f32)>> {
    let bvh = crate::geometry::bvh::Bvh::build(&s.positions, &s.triangles);
    form_factors_of(&s.positions, &s.triangles, p, &settings(method, res), 2.0, &bvh)
}

/// F from polygon a to polygon b: (1/A_a) Σ_{i∈a} A_i Σ_{j∈b} F_ij.
fn polygon_to_polygon(s: &Soup, p: &Patches, rows: &Rows, a: usize, b: usize) -> f64 {
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for i in (0..p.len()).filter(|&i| s.owner[i] == a) {
        let f: f64 = rows[i].iter().filter(|(j, _)| s.owner[*j as usize] == b).map(|(_, f)| *f as f64).sum();
        num += p.area[i] as f64 * f;
        den += p.area[i] as f64;
    }
    num / den
}

fn square(centre: Vec3, u: Vec3, v: Vec3) -> Vec<Vec3> {
    // Counter-clockwise about u × v: that is the side it faces.
    vec![centre - u - v, centre + u - v, centre + u + v, centre - u + v]
}

fn unit_squares_facing() -> Vec<Vec<Vec3>> {
    // Unit squares at y = 0 (facing up) and y = 1 (facing down).
    vec![square(Vec3::ZERO, Vec3::Z * 0.5, Vec3::X * 0.5), square(Vec3::Y, Vec3::X * 0.5, Vec3::Z * 0.5)]
}

/// Parallel unit squares at distance 1: F = 0.19982 (Howell, *A Catalog of Radiation Heat
/// Transfer Configuration Factors*, C-11, with X = Y = 1).
#[test]
fn parallel_unit_squares_by_both_methods() {
    let s = soup(&unit_squares_facing(), 0.15);
    let p = patches(&s, |_| Vec3::ZERO, |_| Vec3::ONE);
    for (method, tol) in [(FormFactorMethod::Hemicube, 0.004), (FormFactorMethod::Ray, 0.001)] {
        let rows = matrix(&s, &p, method, 64);
        let f = polygon_to_polygon(&s, &p, &rows, 0, 1);
        eprintln!("parallel squares, {method:?}, {} patches: F = {f:.5}", p.len());
        assert!((f - 0.19982).abs() < tol, "{method:?}: {f}");
        // Reciprocity: A_a F_ab = A_b F_ba (equal areas).
        let back = polygon_to_polygon(&s, &p, &rows, 1, 0);
        assert!((f - back).abs() < tol, "{method:?}: {f} vs {back}");
    }
}

/// Perpendicular unit squares sharing an edge: F = 0.20004 (Howell C-14 with L = N = 1).
#[test]
fn perpendicular_unit_squares_sharing_an_edge() {
    // A floor [0,1]² at y = 0 facing up and a wall x = 0, y ∈ [0, 1] facing +x.
    let floor = square(Vec3::new(0.5, 0.0, 0.5), Vec3::Z * 0.5, Vec3::X * 0.5);
    let wall = square(Vec3::new(0.0, 0.5, 0.5), Vec3::Y * 0.5, Vec3::Z * 0.5);
    let s = soup(&[floor, wall], 0.1);
    let p = patches(&s, |_| Vec3::ZERO, |_| Vec3::ONE);
    for (method, tol) in [(FormFactorMethod::Hemicube, 0.005), (FormFactorMethod::Ray, 0.002)] {
        let rows = matrix(&s, &p, method, 64);
        let f = polygon_to_polygon(&s, &p, &rows, 0, 1);
        eprintln!("perpendicular squares, {method:?}, {} patches: F = {f:.5}", p.len());
        assert!((f - 0.20004).abs() < tol, "{method:?}: {f}");
    }
}

/// Coaxial unit discs at distance 1: F = (X − √(X² − 4))/2 with X = 3: 0.38197 (Howell C-41).
#[test]
fn coaxial_unit_discs() {
    // 48-gons of the disc's area (radius scaled up by 1/√(n sin(2π/n) / 2π)).
    let n = 48;
    let r = 1.0 / ((n as f64 * (std::f64::consts::TAU / n as f64).sin() / std::f64::consts::TAU).sqrt() as f32);
    let disc = |y: f32, up: bool| -> Vec<Vec3> {
        let mut v: Vec<Vec3> = (0..n)
            .map(|k| {
                let a = std::f32::consts::TAU * k as f32 / n as f32;
                Vec3::new(r * a.cos(), y, -r * a.sin())
            })
            .collect();
        if !up {
            v.reverse();
        }
        v
    };
    let s = soup(&[disc(0.0, true), disc(1.0, false)], 0.3);
    let p = patches(&s, |_| Vec3::ZERO, |_| Vec3::ONE);
    for (method, tol) in [(FormFactorMethod::Hemicube, 0.006), (FormFactorMethod::Ray, 0.003)] {
        let rows = matrix(&s, &p, method, 64);
        let f = polygon_to_polygon(&s, &p, &rows, 0, 1);
        eprintln!("discs, {method:?}, {} patches: F = {f:.5}", p.len());
        assert!((f - 0.38197).abs() < tol, "{method:?}: {f}");
    }
}

/// The inside of a cube, every face facing in.
fn closed_box(size: f32) -> Soup {
    let h = 0.5;
    let faces = vec![
        square(Vec3::new(0.0, -h, 0.0), Vec3::Z * h, Vec3::X * h),
        square(Vec3::new(0.0, h, 0.0), Vec3::X * h, Vec3::Z * h),
        square(Vec3::new(-h, 0.0, 0.0), Vec3::Y * h, Vec3::Z * h),
        square(Vec3::new(h, 0.0, 0.0), Vec3::Z * h, Vec3::Y * h),
        square(Vec3::new(0.0, 0.0, -h), Vec3::X * h, Vec3::Y * h),
        square(Vec3::new(0.0, 0.0, h), Vec3::Y * h, Vec3::X * h),
    ];
    soup(&faces, size)
}

#[test]
fn rows_sum_to_one_in_a_closed_box_and_reciprocity_holds() {
    let s = closed_box(0.25);
    let p = patches(&s, |_| Vec3::ZERO, |_| Vec3::ONE);
    for (method, tol) in [(FormFactorMethod::Hemicube, 2e-3), (FormFactorMethod::Ray, 1e-4)] {
        let rows = matrix(&s, &p, method, 64);
        for (i, r) in rows.iter().enumerate() {
            let sum: f32 = r.iter().map(|(_, f)| f).sum();
            assert!((sum - 1.0).abs() < tol, "{method:?}: row {i} sums to {sum}");
        }
        // Face to face: A_a F_ab = A_b F_ba, and opposite faces of a cube see 0.19982 of each other.
        let f01 = polygon_to_polygon(&s, &p, &rows, 0, 1);
        let f10 = polygon_to_polygon(&s, &p, &rows, 1, 0);
        assert!((f01 - f10).abs() < 3.0 * tol as f64 + 1e-3, "{method:?}: {f01} vs {f10}");
        assert!((f01 - 0.19982).abs() < 0.01, "{method:?}: {f01}");
    }
}

/// A closed box of uniform reflectance ρ whose every patch emits E: L = E + ρL, so
/// L = E / (1 − ρ) everywhere, for every solver.
#[test]
fn uniform_closed_box_gives_e_over_one_minus_rho() {
    let s = closed_box(0.34);
    let (e, rho) = (Vec3::new(1.0, 2.0, 0.5), Vec3::new(0.5, 0.8, 0.3));
    let p = patches(&s, |_| e, |_| rho);
    let rows = matrix(&s, &p, FormFactorMethod::Ray, 64);
    let exact = e / (Vec3::ONE - rho);
    for solver in [Solver::Jacobi, Solver::GaussSeidel, Solver::Progressive] {
        // 10⁻⁵ of E: a few f32 roundings of L = 10.
        let st = RadiositySettings { solver, iterations: 1000, tolerance: 1e-5, ..RadiositySettings::default() };
        let sol = solve::solve(&rows, &p.emission, &p.reflectance, &p.area, &st);
        for l in &sol.radiance {
            assert!(((*l - exact) / exact).abs().max_element() < 1e-3, "{solver:?}: {l} vs {exact}");
        }
        assert!(sol.residual() <= 1e-5, "{solver:?}: {}", sol.residual());
    }
}

/// One emitting face in a closed box: the power emitted, π Σ A_i E_i, is all absorbed,
/// π Σ A_i (1 − ρ_i) H_i with H_i = Σ_j F_ij L_j, once converged.
#[test]
fn energy_is_conserved_in_a_closed_box() {
    let s = closed_box(0.25);
    let e = |o: usize| if o == 1 { Vec3::splat(5.0) } else { Vec3::ZERO };
    let rho = |o: usize| {
        [Vec3::splat(0.7), Vec3::splat(0.2), Vec3::new(0.63, 0.065, 0.05), Vec3::new(0.14, 0.45, 0.091), Vec3::splat(0.5), Vec3::splat(0.9)]
            [o]
    };
    let p = patches(&s, e, rho);
    for method in [FormFactorMethod::Ray, FormFactorMethod::Hemicube] {
        let rows = matrix(&s, &p, method, 64);
        let st = RadiositySettings { iterations: 1000, tolerance: 1e-6, ..RadiositySettings::default() };
        let sol = solve::solve(&rows, &p.emission, &p.reflectance, &p.area, &st);
        let emitted: Vec3 = (0..p.len()).map(|i| p.emission[i] * p.area[i]).sum();
        let absorbed: Vec3 = (0..p.len())
            .map(|i| {
                let h = rows[i].iter().fold(Vec3::ZERO, |a, &(j, f)| a + sol.radiance[j as usize] * f);
                (Vec3::ONE - p.reflectance[i]) * h * p.area[i]
            })
            .sum();
        assert!(((absorbed - emitted) / emitted).abs().max_element() < 3e-3, "{method:?}: {absorbed} vs {emitted}");
    }
}

/// Jacobi's iterate k is the Neumann series to k bounces: one iteration gives E + ρFE.
#[test]
fn one_jacobi_iteration_is_one_bounce() {
    let s = closed_box(0.5);
    let p = patches(&s, |o| if o == 1 { Vec3::ONE } else { Vec3::ZERO }, |_| Vec3::splat(0.5));
    let rows = matrix(&s, &p, FormFactorMethod::Ray, 64);
    let st = RadiositySettings { solver: Solver::Jacobi, iterations: 1, tolerance: 0.0, ..RadiositySettings::default() };
    let sol = solve::solve(&rows, &p.emission, &p.reflectance, &p.area, &st);
    assert_eq!(sol.iterations, 1);
    assert_eq!(sol.residuals.len(), 2);
    for (i, row) in rows.iter().enumerate() {
        let bounce = row.iter().fold(Vec3::ZERO, |a, &(j, f)| a + p.emission[j as usize] * f);
        let want = p.emission[i] + p.reflectance[i] * bounce;
        assert!((sol.radiance[i] - want).abs().max_element() < 1e-6);
    }
}

/// Coincident patches and a zero-area patch:
/// every form factor and radiance stays finite, and the zero-area patch exchanges nothing.
#[test]
fn no_nan_with_coincident_or_zero_area_patches() {
    let mut s = closed_box(0.5);
    let dup = s.triangles[3];
    let n3 = s.normals[3];
    s.triangles.push(dup);
    s.normals.push(n3);
    s.owner.push(0);
    let base = s.positions.len() as u32;
    s.positions.extend([Vec3::splat(0.1), Vec3::splat(0.1), Vec3::splat(0.1)]);
    s.triangles.push([base, base + 1, base + 2]);
    s.normals.push(Vec3::Y);
    s.owner.push(1);
    let p = patches(&s, |o| if o == 1 { Vec3::ONE } else { Vec3::ZERO }, |_| Vec3::splat(0.5));
    assert_eq!(p.area[p.len() - 1], 0.0);
    for method in [FormFactorMethod::Hemicube, FormFactorMethod::Ray] {
        let rows = matrix(&s, &p, method, 32);
        assert!(rows.iter().flatten().all(|(_, f)| f.is_finite() && *f >= 0.0));
        assert!(rows[p.len() - 1].is_empty());
        assert!(rows.iter().all(|r| r.iter().all(|(j, _)| *j as usize != p.len() - 1)));
        for solver in [Solver::Jacobi, Solver::GaussSeidel, Solver::Progressive] {
            let st = RadiositySettings { solver, ambient_correction: true, ..RadiositySettings::default() };
            let sol = solve::solve(&rows, &p.emission, &p.reflectance, &p.area, &st);
            assert!(sol.radiance.iter().all(|l| l.is_finite() && l.min_element() >= 0.0));
        }
    }
}

/// The three solvers reach the same solution; Gauss-Seidel in fewer sweeps than Jacobi.
#[test]
fn solvers_agree_and_gauss_seidel_is_faster() {
    let s = closed_box(0.34);
    let p = patches(&s, |o| if o == 1 { Vec3::splat(3.0) } else { Vec3::ZERO }, |o| Vec3::splat(0.3 + 0.1 * o as f32));
    let rows = matrix(&s, &p, FormFactorMethod::Ray, 64);
    let run = |solver| {
        let st = RadiositySettings { solver, iterations: 1000, tolerance: 1e-5, ..RadiositySettings::default() };
        solve::solve(&rows, &p.emission, &p.reflectance, &p.area, &st)
    };
    let (j, g, pr) = (run(Solver::Jacobi), run(Solver::GaussSeidel), run(Solver::Progressive));
    for i in 0..p.len() {
        assert!((j.radiance[i] - g.radiance[i]).abs().max_element() < 1e-3);
        assert!((j.radiance[i] - pr.radiance[i]).abs().max_element() < 1e-3);
    }
    assert!(g.iterations < j.iterations, "{} vs {}", g.iterations, j.iterations);
    // Residuals fall monotonically for Jacobi (a contraction with ρ < 1 in a closed box).
    assert!(j.residuals.windows(2).all(|w| w[1] <= w[0]));
}

/// Every solver reaches a tight tolerance: progressive refinement too, whose f32 running sums
/// once lost the late shots (its residual stalled near 1e-5 on lesson 27's box). Below about
/// 1e-7 the residual itself, gathered in f32, is noise.
#[test]
fn every_solver_reaches_a_tight_tolerance() {
    let s = closed_box(0.25);
    let p = patches(&s, |o| if o == 1 { Vec3::splat(17.0) } else { Vec3::ZERO }, |o| Vec3::splat(0.5 + 0.05 * o as f32));
    let rows = matrix(&s, &p, FormFactorMethod::Ray, 64);
    for solver in Solver::ALL {
        let st = RadiositySettings { solver, iterations: 200, tolerance: 1e-6, ..RadiositySettings::default() };
        let sol = solve::solve(&rows, &p.emission, &p.reflectance, &p.area, &st);
        assert!(sol.residual() <= 1e-6, "{}: residual {:e} after {} iterations", solver.name(), sol.residual(), sol.iterations);
        assert!(sol.iterations < 200, "{}", solver.name());
    }
}
