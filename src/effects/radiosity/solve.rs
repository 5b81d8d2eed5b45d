//! The solvers of the radiosity system, in radiance: L_i = E_i + ρ_i Σ_j F_ij L_j
//! (Goral et al. 1984, eq. 1, divided by π: B = πL, and a patch with emission E emits πE
//! per unit area, docs/conventions.md).
//!
//! - **Jacobi** gathering: L⁽ᵏ⁺¹⁾ = E + ρ ⊙ F L⁽ᵏ⁾; iterate k holds exactly the light of
//!   paths with at most k bounces (Neumann series), which is what the `iterations` ladder shows.
//! - **Gauss-Seidel** gathering: the same sweep, each patch gathering from the newest values
//!   (Cohen & Greenberg 1985 solve this way); it converges about twice as fast.
//! - **Progressive refinement** (Cohen, Chen, Wallace & Greenberg, SIGGRAPH 1988): the patch
//!   with the most unshot power ΔL_i A_i shoots it to every patch j that sees it,
//!   ΔL_j += ρ_j F_ji ΔL_i. The paper takes F_ji = F_ij A_i / A_j (reciprocity) from the
//!   shooter's own hemicube, so that only row i is ever needed; with the whole matrix at hand
//!   the column (j, F_ji) is read instead, so that all three solvers solve the same system.
//!   (Point-to-area form factors are not exactly reciprocal: on a closed box of 3 × 3
//!   patches a face, shooting with F_ij A_i / A_j converged 1.6 % away from E / (1 − ρ).)
//!   One iteration here is N shots, the work of one gathering sweep. The optional ambient
//!   correction (their §4) adds ρ_i L_amb, L_amb = Σ ΔL_i A_i / ΣA_i / (1 − ρ_avg), to the
//!   display only: the unshot light, spread evenly, bounced as in an average room.
//!
//! Every solver starts from L⁽⁰⁾ = E and reports the relative residual
//! r = Σ_i A_i |E_i + ρ_i Σ_j F_ij L_j − L_i| / Σ_i A_i L_i after each iteration (largest
//! channel of each): the share of the room's light that is not yet settled. A residual
//! relative to max E stopped far too early: the emitter's E = 17 dwarfs the walls' L ≈ 0.5,
//! and at 10⁻³ of it Jacobi stopped after 4 bounces with a quarter of the indirect light
//! of lesson 27's box missing.

use crate::lesson::settings::{RadiositySettings, Solver};
use glam::{DVec3, Vec3};

/// A sparse form-factor matrix: row i lists (j, F_ij) for the patches i sees.
pub type Rows = [Vec<(u32, f32)>];

/// A solution and how it was reached.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Radiance L_i per patch (the ambient correction included when asked for).
    pub radiance: Vec<Vec3>,
    /// Iterations run.
    pub iterations: u32,
    /// Relative residual after each iteration, the first entry for L⁽⁰⁾ = E.
    pub residuals: Vec<f32>,
}

impl Solution {
    /// The relative residual of the returned radiances (before any ambient correction).
    pub fn residual(&self) -> f32 {
        self.residuals.last().copied().unwrap_or(0.0)
    }
}

/// Σ_j F_ij L_j for patch i.
#[inline]
fn gathered(row: &[(u32, f32)], l: &[Vec3]) -> Vec3 {
    row.iter().fold(Vec3::ZERO, |s, &(j, f)| s + l[j as usize] * f)
}

/// Σ_i A_i |E_i + ρ_i Σ_j F_ij L_j − L_i| / Σ_i A_i L_i, largest channel of each (0 when
/// nothing shines), summed in f64.
pub fn residual(rows: &Rows, e: &[Vec3], rho: &[Vec3], area: &[f32], l: &[Vec3]) -> f32 {
    let scale: f64 = (0..l.len()).map(|i| area[i] as f64 * l[i].max_element() as f64).sum();
    if scale.is_nan() || scale <= 0.0 {
        return 0.0;
    }
    let r: f64 = (0..l.len()).map(|i| area[i] as f64 * (e[i] + rho[i] * gathered(&rows[i], l) - l[i]).abs().max_element() as f64).sum();
    (r / scale) as f32
}

/// Solves with the settings' solver, `iterations` at most, stopping early once the residual
/// is at most `tolerance`. `area` is needed by progressive refinement.
pub fn solve(rows: &Rows, e: &[Vec3], rho: &[Vec3], area: &[f32], s: &RadiositySettings) -> Solution {
    let n = e.len();
    let mut l = e.to_vec();
    let mut residuals = vec![residual(rows, e, rho, area, &l)];
    // Progressive refinement accumulates in f64: a shot adds ρ F ΔL, soon below one f32 ulp
    // of L, and in f32 those adds were lost (its residual stalled at 1e-5 on lesson 27).
    let mut shot_l: Vec<DVec3> = e.iter().map(|x| x.as_dvec3()).collect();
    let mut unshot = shot_l.clone();
    // Progressive refinement shoots along columns: (j, F_ji) for each shooter i.
    let columns = if s.solver == Solver::Progressive { transpose(rows, n) } else { Vec::new() };
    let mut iterations = 0;
    while iterations < s.iterations && residuals.last().is_some_and(|&r| r > s.tolerance) {
        match s.solver {
            Solver::Jacobi => {
                l = (0..n).map(|i| e[i] + rho[i] * gathered(&rows[i], &l)).collect();
            }
            Solver::GaussSeidel => {
                for i in 0..n {
                    l[i] = e[i] + rho[i] * gathered(&rows[i], &l);
                }
            }
            Solver::Progressive => {
                for _ in 0..n {
                    shoot(&columns, rho, area, &mut shot_l, &mut unshot);
                }
                l = shot_l.iter().map(|x| x.as_vec3()).collect();
            }
        }
        iterations += 1;
        residuals.push(residual(rows, e, rho, area, &l));
    }
    if s.solver == Solver::Progressive && s.ambient_correction {
        let amb = ambient(rho, area, &unshot);
        for i in 0..n {
            l[i] += rho[i] * amb;
        }
    }
    Solution { radiance: l, iterations, residuals }
}

/// The columns of the matrix: for each patch i, (j, F_ji) over the patches j that see i.
fn transpose(rows: &Rows, n: usize) -> Vec<Vec<(u32, f32)>> {
    let mut columns = vec![Vec::new(); n];
    for (j, row) in rows.iter().enumerate() {
        for &(i, f) in row {
            columns[i as usize].push((j as u32, f));
        }
    }
    columns
}

/// One shot of progressive refinement: the patch with the most unshot power sends it.
fn shoot(columns: &Rows, rho: &[Vec3], area: &[f32], l: &mut [DVec3], unshot: &mut [DVec3]) {
    // Power ∝ ΔL_i A_i (summed over channels); ties go to the lower index (deterministic).
    let (i, power) = unshot.iter().zip(area).enumerate().fold((0, 0.0f64), |best, (i, (u, a))| {
        let p = (u.x + u.y + u.z) * *a as f64;
        if p > best.1 { (i, p) } else { best }
    });
    if power <= 0.0 {
        return;
    }
    let du = unshot[i];
    unshot[i] = DVec3::ZERO;
    for &(j, f) in &columns[i] {
        let j = j as usize;
        // f = F_ji: what j gathers from i.
        let add = rho[j].as_dvec3() * du * f as f64;
        l[j] += add;
        unshot[j] += add;
    }
}

/// Cohen et al. 1988's ambient term: the unshot radiance spread over the whole area,
/// times the interreflection factor 1 / (1 − ρ_avg) (ρ_avg area-weighted), per channel.
fn ambient(rho: &[Vec3], area: &[f32], unshot: &[DVec3]) -> Vec3 {
    let total: f32 = area.iter().sum();
    if total <= 0.0 {
        return Vec3::ZERO;
    }
    let avg_unshot = unshot.iter().zip(area).fold(Vec3::ZERO, |s, (u, a)| s + u.as_vec3() * *a) / total;
    let rho_avg = rho.iter().zip(area).fold(Vec3::ZERO, |s, (r, a)| s + *r * *a) / total;
    // ρ_avg < 1 is kept by the clamp in `reflectance`; the min keeps 1/(1 − ρ) finite at 1.
    avg_unshot / (Vec3::ONE - rho_avg).max(Vec3::splat(1e-3))
}
