//! How `explain --pixel` prints a [`PixelReport`]: text in `explain`'s notation, or one
//! JSON object per pixel (`--format jsonl`; fields in docs/cli.md, "Explain a pixel").

use crate::lesson::i18n::Lang;
use crate::render::explain::pad;
use crate::render::pipeline::LitBy;
use crate::render::pixel::{LightReport, PixelReport, SurfaceReport};
use crate::scene::{ClassicModel, Model, Scene};
use crate::shading::Components;
use glam::Vec3;
use serde_json::{Value, json};

/// `writeln!` into a `String`, which cannot fail.
macro_rules! wln {
    ($s:expr, $($arg:tt)*) => {{
        $s.push_str(&format!($($arg)*));
        $s.push('\n');
    }};
}

/// A number with four significant digits (no exponent between 10⁻⁴ and 10⁶).
pub fn num(x: f32) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return if x.is_nan() {
            "NaN".into()
        } else if x > 0.0 {
            "∞".into()
        } else {
            "−∞".into()
        };
    }
    let a = x.abs();
    if !(1e-4..1e6).contains(&a) {
        return format!("{x:.3e}");
    }
    let digits = (3 - a.log10().floor() as i32).clamp(0, 7) as usize;
    let s = format!("{x:.digits$}");
    if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s }
}

/// A vector as (x, y, z).
pub fn vec3(v: Vec3) -> String {
    format!("({}, {}, {})", num(v.x), num(v.y), num(v.z))
}

/// The explanation of one pixel as text.
pub fn text(r: &PixelReport, scene: &Scene, lang: Lang) -> String {
    let tr = |t: &'static str| lang.tr(t);
    let mut s = String::new();
    let (x, y) = r.pixel;
    let Some(surf) = &r.surface else {
        wln!(s, "{} ({x}, {y}): {}", tr("pixel"), tr("the background: no surface is seen here, nothing is shaded"));
        wln!(s, "  {} = {}   sRGB = {:?}", tr("rendered (linear)"), vec3(r.linear), r.srgb);
        return s;
    };
    let how = match surf.lit_by {
        LitBy::Sample => "lit at this sample (Phong interpolation)",
        LitBy::Vertices => "lit at the triangle's vertices, their values interpolated (Gouraud)",
        LitBy::Face => "lit once per face at its centroid (flat)",
        LitBy::Radiosity => "lit by the radiosity solution",
    };
    wln!(
        s,
        "{} ({x}, {y}): object {} ({} {}), material \"{}\" ({}), {}",
        tr("pixel"),
        surf.object,
        tr("triangle"),
        surf.triangle,
        surf.material,
        surf.model,
        tr(how)
    );
    if r.aa > 1 {
        wln!(s, "  {}", lang.say(&format!("aa = {}: this explains the pixel's centre sample, rendered alone at aa = 1", r.aa)));
    }
    wln!(s, "  p = {}   V = {}", vec3(surf.position), vec3(surf.v));
    wln!(s, "  N = {}   N_g = {} ({})", vec3(surf.n), vec3(surf.ng), tr("face normal"));
    if !surf.vertices.is_empty() {
        wln!(s, "  {}", tr("Gouraud: the vertices' lit values, weighted by the sample's barycentrics"));
        for v in &surf.vertices {
            wln!(s, "    vertex {}: {} {}  N = {}  I = {}", v.vertex, tr("weight"), num(v.weight), vec3(v.n), vec3(v.total));
        }
    }
    let m = &scene.materials[scene.materials.iter().position(|m| m.name == surf.material).unwrap_or(0)];
    for l in &surf.lights {
        light_text(&mut s, l, m, surf, lang);
    }
    if surf.radiosity.is_none() {
        wln!(s, "  {} K_amb ⊗ L_glob = {}", tr("global ambient"), vec3(surf.global_ambient));
        if surf.emission != Vec3::ZERO {
            wln!(s, "  {} = {}", tr("emission"), vec3(surf.emission));
        }
        if surf.recomputed.reflection != Vec3::ZERO {
            // Which estimator the environment's light went through, when there is one.
            let how = match &scene.environment {
                Some(_) => format!(" [ibl = {}]", scene.spec.settings.ibl.name()),
                None => String::new(),
            };
            wln!(s, "  {}{how} = {}", tr("reflection (environment, mirrors)"), vec3(surf.recomputed.reflection));
        }
        if surf.recomputed.transmission != Vec3::ZERO {
            wln!(s, "  {} = {}", tr("transmission (glass)"), vec3(surf.recomputed.transmission));
        }
        wln!(s, "  {} = {}", tr("sum of the terms"), vec3(surf.recomputed.total()));
    } else {
        wln!(s, "  {} B = {}", tr("radiosity of the patch (all lights, all bounces)"), vec3(surf.recomputed.total()));
    }
    if let Some(f) = surf.fog {
        wln!(s, "  {} = {}", tr("fog (in-scattered light − what the fog absorbed)"), vec3(f));
    }
    wln!(s, "  {} = {}", tr("rendered sample (linear)"), vec3(r.sample));
    if let Some(d) = r.difference() {
        wln!(s, "  {} = {}", tr("rendered − sum"), vec3(d));
    }
    if r.aa > 1 {
        wln!(s, "  {} = {}", lang.say(&format!("rendered pixel, mean of {} samples", r.aa * r.aa)), vec3(r.linear));
    }
    let exposed = r.linear * r.exposure.exp2();
    let mapped = crate::render::develop::tonemap_rgb(exposed, r.tonemap);
    wln!(
        s,
        "  × 2^{} ({}) = {} → {} {}: {} → sRGB ({}, {}, {})",
        num(r.exposure),
        tr("exposure in stops"),
        vec3(exposed),
        tr("tone map"),
        r.tonemap.name(),
        vec3(mapped),
        r.srgb[0],
        r.srgb[1],
        r.srgb[2]
    );
    s
}

/// One light's lines.
fn light_text(s: &mut String, l: &LightReport, m: &crate::scene::Material, surf: &SurfaceReport, lang: Lang) {
    let tr = |t: &'static str| lang.tr(t);
    let samples = if l.incidents > 1 { format!(", {} {}", l.incidents, tr("incidents (means below)")) } else { String::new() };
    wln!(s, "  {} {} ({}{samples})", tr("light"), l.index, l.kind);
    let shadow = match (l.shadow, l.occluder) {
        (None, _) => tr("no shadows").to_string(),
        (Some(m), Some(o)) => format!("{}: {} {o}", m.name(), tr("blocked by object")),
        (Some(m), None) if l.visibility >= 1.0 => format!("{}: {}", m.name(), tr("unblocked")),
        (Some(m), None) if l.visibility <= 0.0 => format!("{}: {}", m.name(), tr("blocked")),
        (Some(m), None) => format!("{}: {}", m.name(), tr("partly blocked")),
    };
    let r = if l.distance.is_finite() { num(l.distance) } else { "∞".into() };
    wln!(
        s,
        "    L = {}  r = {r}  d = {}  C_spot = {}  {} = {} ({shadow})",
        vec3(l.l),
        num(l.attenuation),
        num(l.c_spot),
        tr("visibility"),
        num(l.visibility)
    );
    if let Some(m) = &l.map {
        let verdict = if m.biased > m.stored { tr("farther: in shadow") } else { tr("not farther: lit") };
        let stored = if m.stored.is_finite() { num(m.stored) } else { "∞".into() };
        wln!(
            s,
            "    {}: {stored}; {}: {} ({} {}) → {verdict}",
            tr("shadow map, nearest surface the light sees at the point's texel"),
            tr("the point"),
            num(m.point),
            tr("after the bias"),
            num(m.biased)
        );
    }
    wln!(s, "    N·L = {}  R = {}  R·V = {}  H = {}  N·H = {}", num(l.n_dot_l), vec3(l.r), num(l.r_dot_v), vec3(l.h), num(l.n_dot_h));
    match &m.model {
        Model::Classic(c) => {
            let spec = match c.model {
                ClassicModel::Phong => format!("K_spec max(R·V, 0)^{} d C_spot v L_spec", num(c.shininess)),
                ClassicModel::BlinnPhong => format!("K_spec max(N·H, 0)^{} d C_spot v L_spec", num(c.shininess)),
                ClassicModel::Lambert => "0 (Lambert)".into(),
            };
            wln!(s, "    {} C_spot K_amb ⊗ L_amb = {}", pad(tr("ambient"), 9), vec3(l.terms.ambient));
            let n_dot_l = if c.clamp_n_dot_l { "max(N·L, 0)" } else { "(N·L, unclamped)" };
            wln!(s, "    {} K_diff {n_dot_l} d C_spot v L_diff = {}", pad(tr("diffuse"), 9), vec3(l.terms.diffuse));
            wln!(s, "    {} {spec} = {}", pad(tr("specular"), 9), vec3(l.terms.specular));
        }
        Model::Physical(_) => {
            if let Some(b) = &l.brdf {
                if let Some((d, g, f)) = b.dgf {
                    wln!(s, "    D = {}  G = {}  F = {}", num(d), num(g), vec3(f));
                }
                wln!(s, "    f = f_d + f_s = {} + {} (1/sr)  cos θ = {}", vec3(b.f_diffuse), vec3(b.f_specular), num(b.cos_theta));
            }
            wln!(s, "    {} f_d E cos θ v = {}", pad(tr("diffuse"), 9), vec3(l.terms.diffuse));
            wln!(s, "    {} f_s E cos θ v = {}", pad(tr("specular"), 9), vec3(l.terms.specular));
            if l.terms.ambient != Vec3::ZERO {
                wln!(s, "    {} C_spot K_amb ⊗ L_amb = {}", pad(tr("ambient"), 9), vec3(l.terms.ambient));
            }
        }
        Model::Mirror(_) | Model::Glass(_) => wln!(s, "    {}", tr("a delta BRDF: no light reaches the eye from this light directly")),
    }
    if surf.lit_by == LitBy::Vertices {
        wln!(s, "    {}", tr("(vectors at the sample; the terms are the vertices' values, interpolated)"));
    }
}

/// An `f32` as the shortest decimal that reads back as it (not the `f64` widening's digits).
fn f(x: f32) -> Value {
    if x.is_finite() { x.to_string().parse::<f64>().map_or(Value::Null, |d| json!(d)) } else { Value::Null }
}

fn v3(v: Vec3) -> Value {
    json!([f(v.x), f(v.y), f(v.z)])
}

fn terms(c: &Components) -> Value {
    json!({
        "emission": v3(c.emission),
        "ambient": v3(c.ambient),
        "diffuse": v3(c.diffuse),
        "specular": v3(c.specular),
        "reflection": v3(c.reflection),
        "transmission": v3(c.transmission),
    })
}

/// The explanation of one pixel as one JSON object (`--format jsonl`).
pub fn json(r: &PixelReport) -> Value {
    let mut o = json!({
        "pixel": [r.pixel.0, r.pixel.1],
        "aa": r.aa,
        "linear": v3(r.linear),
        "srgb": r.srgb,
        "sample": v3(r.sample),
        "layers": terms(&r.layers),
        "exposure": f(r.exposure),
        "tonemap": r.tonemap.name(),
        "background": r.surface.is_none(),
        "object": Value::Null,
        "material": Value::Null,
        "lights": [],
    });
    let Some(s) = &r.surface else { return o };
    let lights: Vec<Value> = s
        .lights
        .iter()
        .map(|l| {
            let mut v = json!({
                "light": l.index,
                "kind": l.kind,
                "incidents": l.incidents,
                "l": v3(l.l),
                "distance": f(l.distance),
                "attenuation": f(l.attenuation),
                "c_spot": f(l.c_spot),
                "visibility": f(l.visibility),
                "shadow": l.shadow.map(|m| m.name()),
                "occluder": l.occluder,
                "map": l.map.map(|m| json!({"face": m.face, "texel": [m.texel.0, m.texel.1], "stored": f(m.stored), "point": f(m.point), "biased": f(m.biased)})),
                "n_dot_l": f(l.n_dot_l),
                "r": v3(l.r),
                "r_dot_v": f(l.r_dot_v),
                "h": v3(l.h),
                "n_dot_h": f(l.n_dot_h),
                "terms": terms(&l.terms),
            });
            if let Some(b) = &l.brdf {
                v["brdf"] = json!({
                    "f_diffuse": v3(b.f_diffuse),
                    "f_specular": v3(b.f_specular),
                    "cos_theta": f(b.cos_theta),
                    "d": b.dgf.map(|t| f(t.0)),
                    "g": b.dgf.map(|t| f(t.1)),
                    "f": b.dgf.map(|t| v3(t.2)),
                });
            }
            v
        })
        .collect();
    o["object"] = json!(s.object);
    o["material"] = json!(s.material);
    o["model"] = json!(s.model);
    o["triangle"] = json!(s.triangle);
    o["position"] = v3(s.position);
    o["v"] = v3(s.v);
    o["n"] = v3(s.n);
    o["ng"] = v3(s.ng);
    o["lit_by"] = json!(match s.lit_by {
        LitBy::Sample => "sample",
        LitBy::Vertices => "vertices",
        LitBy::Face => "face",
        LitBy::Radiosity => "radiosity",
    });
    o["vertices"] =
        s.vertices.iter().map(|v| json!({"vertex": v.vertex, "weight": f(v.weight), "n": v3(v.n), "total": v3(v.total)})).collect();
    o["lights"] = Value::Array(lights);
    o["global_ambient"] = v3(s.global_ambient);
    o["emission"] = v3(s.emission);
    o["terms"] = terms(&s.recomputed);
    o["fog"] = s.fog.map_or(Value::Null, v3);
    o["difference"] = r.difference().map_or(Value::Null, v3);
    o
}
