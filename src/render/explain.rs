//! What `shadelab explain` prints: each material's equation with its values, the plan's
//! passes, terms and lights with their reasons, and (after one render) what ran. One text
//! for the terminal and for the lesson pages of `shadelab site`.

use crate::lesson::i18n::Lang;
use crate::render::plan::{Decision, plan};
use crate::scene::{ClassicModel, Material, Model, Scene};
use glam::Vec3;

/// `writeln!` into a `String`, which cannot fail.
macro_rules! wln {
    ($s:expr) => {
        $s.push('\n')
    };
    ($s:expr, $($arg:tt)*) => {{
        $s.push_str(&format!($($arg)*));
        $s.push('\n');
    }};
}

/// The explanation of `scene`: materials, lights and passes; with `render`, one render's
/// counts too (and, for radiosity, each solver's residuals).
pub fn text(scene: &Scene, render: bool, lang: Lang) -> String {
    let mut s = String::new();
    let p = plan(scene);
    let tr = |t: &'static str| lang.tr(t);
    let line = |d: &Decision| line(d, lang);
    wln!(s, "{}", tr("Materials"));
    for (m, terms) in scene.materials.iter().zip(&p.terms) {
        let (symbolic, values) = equation(m, scene.spec.ambient, scene.spec.settings.method == crate::lesson::settings::RenderMethod::Path);
        let model = m.family_name();
        wln!(s, "  {} ({model})", m.name);
        wln!(s, "    {symbolic}");
        wln!(s, "    {values}");
        for t in terms {
            wln!(s, "  {}", line(t));
        }
        wln!(s);
    }
    wln!(s, "{}", tr("Lights"));
    if p.lights.is_empty() {
        wln!(s, "  {}", tr("(none)"));
    }
    for (d, sh) in p.lights.iter().zip(&p.shadows) {
        wln!(s, "{}", line(d));
        if d.runs && scene.spec.settings.method == crate::lesson::settings::RenderMethod::Path {
            // Light transport has no shadow method: every next-event sample is a shadow ray.
            let what = format!("  {}: {}", tr("shadows"), tr("ray"));
            let why = "the path tracer traces a shadow ray for every sample (`shadows` is the rasterizer's choice)";
            wln!(s, "{}", line(&Decision { what, runs: true, why: why.into() }));
        } else if d.runs {
            let method = sh.method.map_or("none", |m| m.name());
            let what = format!("  {}: {}", tr("shadows"), tr(method));
            wln!(s, "{}", line(&Decision { what, runs: sh.method.is_some(), why: sh.why.into() }));
        }
    }
    wln!(s, "\n{}", tr("Passes"));
    for step in &p.passes {
        wln!(s, "{}", line(&Decision { what: step.pass.name().into(), runs: step.runs, why: step.why.clone() }));
    }
    let estimate = crate::render::budget::estimate(scene);
    wln!(s, "\n{}", tr("Estimate (from the plan, before any work)"));
    wln!(s, "  {}", lang.say(&estimate.summary()));
    for row in estimate.table(lang) {
        wln!(s, "    {row}");
    }
    let allowed = crate::render::budget::check(scene);
    if let Err(e) = &allowed {
        wln!(s, "  {}", lang.say("over the budget: no render (raise it with --budget)"));
        for l in e.0.lines().skip(1) {
            wln!(s, "  {l}");
        }
    }
    if render && allowed.is_ok() {
        let start = web_time::Instant::now();
        let (_, st) = crate::render::render(scene, &[crate::render::Layer::Total]);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        wln!(s, "\n{}, {ms:.1} ms)", tr("What ran (one render"));
        if let Some(peak) = crate::render::budget::peak_bytes() {
            wln!(s, "  {} {:>12}", pad(tr("peak memory of the process"), 40), crate::render::budget::bytes(peak));
        }
        let ran: Vec<&str> = crate::render::plan::Pass::ALL.iter().filter(|p| st.passes & p.bit() != 0).map(|p| tr(p.name())).collect();
        wln!(s, "  {}: {}", tr("passes"), ran.join(", "));
        for (what, n) in counts(&st) {
            wln!(s, "  {} {n:>12}", pad(tr(what), 40));
        }
        if scene.spec.settings.method == crate::lesson::settings::RenderMethod::Radiosity {
            radiosity(scene, &mut s, lang);
        }
        let paths = st.counters.get(crate::transport::path::PATHS);
        if paths > 0 {
            let mean = st.counters.get(crate::transport::path::SEGMENTS) as f64 / paths as f64;
            wln!(s, "  {} {mean:>12.2}", pad(tr("mean path length (segments)"), 40));
        }
        if p.running().any(|s| s == crate::render::plan::Pass::ProbeCapture) {
            // The capture alone, timed again: the six renders per probe before the frame.
            let start = web_time::Instant::now();
            let maps = crate::render::probe::capture(scene);
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let plural = if maps.len() == 1 { "" } else { "s" };
            wln!(s, "\n{}", lang.say(&format!("Probe capture ({} probe{plural}, six faces each): {ms:.1} ms", maps.len())));
        }
    }
    s
}

/// A colour as a person writes it: `0.5` for a grey, `[0.7, 0.04, 0.03]` otherwise.
fn show(c: Vec3) -> String {
    let f = |x: f32| format!("{}", (x * 1e4).round() / 1e4);
    if c.x == c.y && c.y == c.z { f(c.x) } else { format!("[{}, {}, {}]", f(c.x), f(c.y), f(c.z)) }
}

/// The course equation of a classic material, symbolic and with its values.
fn equation(m: &Material, global: Vec3, path: bool) -> (String, String) {
    let c = match &m.model {
        Model::Classic(c) => c,
        Model::Mirror(mirror) => {
            return (
                "L_o = L_emi + tint⊗L_i(r),  r = 2(n·v)n − v    (L_i: the environment or the object the reflected ray hits)".into(),
                format!("  L_emi = {}, tint = {}", show(m.emission), show(mirror.tint)),
            );
        }
        Model::Glass(glass) => {
            return (
                "L_o = L_emi + F L_i(r) + (1 − F) tint⊗L_i(t),  F = F_dielectric(n·v, η),  t: Snell's refraction of v    (total internal reflection: F = 1)".into(),
                format!(
                    "  L_emi = {}, η = {}, tint = {}, {}",
                    show(m.emission),
                    show(glass.ior),
                    show(glass.tint),
                    if glass.thin { "thin (one interface)" } else { "a solid: rays refract in and out" }
                ),
            );
        }
        Model::Physical(brdf) if path => {
            return (
                "L_o = L_emi + ∫ f(l, v) L_i(l) (n·l) dω_l    (the rendering equation, Kajiya 1986: L_i is the L_o of whatever the path meets next)".into(),
                format!("  L_emi = {}; {}", show(m.emission), crate::shading::physical::describe(brdf)),
            );
        }
        Model::Physical(brdf) => {
            return (
            "L_o = K_amb⊗L_glob + L_emi + Σ_k C_spot^k f(l, v) E_k (n·l)    (E = irradiance at normal incidence; I/r² for point lights)"
                .into(),
            format!(
                "  K_amb = {}, L_glob = {}, L_emi = {}; {}",
                show(m.ambient),
                show(global),
                show(m.emission),
                crate::shading::physical::describe(brdf)
            ),
        );
        }
    };
    let spec = match c.model {
        ClassicModel::Lambert => ("", String::new()),
        ClassicModel::Phong => {
            (" + max(R·V, 0)^K_shi K_spec⊗L_spec", format!(" + max(R·V, 0)^{} {}⊗L_spec", c.shininess, show(c.specular)))
        }
        ClassicModel::BlinnPhong => {
            (" + max(N·H, 0)^K_shi K_spec⊗L_spec", format!(" + max(N·H, 0)^{} {}⊗L_spec", c.shininess, show(c.specular)))
        }
    };
    // `clamp_n_dot_l = false` shows in the equation it changes.
    let n_dot_l = if c.clamp_n_dot_l { "max(N·L, 0)" } else { "(N·L, unclamped)" };
    let symbolic = format!("I = L_glob⊗K_amb + L_emi + Σ_k C_spot^k {{ K_amb⊗L_amb^k + d^k ({n_dot_l} K_diff⊗L_diff{}) }}", spec.0);
    let values = format!(
        "  = {}⊗{} + {} + Σ_k C_spot^k {{ {}⊗L_amb^k + d^k ({n_dot_l} {}⊗L_diff{}) }}",
        show(global),
        show(m.ambient),
        show(m.emission),
        show(m.ambient),
        show(c.diffuse),
        spec.1
    );
    (symbolic, values)
}

/// One decision as a line: what, runs or skipped, why (each in `lang`).
fn line(d: &Decision, lang: Lang) -> String {
    let what = match d.what.strip_prefix("  ") {
        // An indented sub-decision (a light's shadows) keeps its indent.
        Some(rest) => format!("  {}", lang.say(rest)),
        None => lang.say(&d.what),
    };
    format!("  {} {} {}", pad(&what, 24), pad(lang.tr(if d.runs { "runs" } else { "skipped" }), 8), lang.say(&d.why))
}

/// `s` padded with spaces to `width` terminal columns: CJK characters take two, so
/// Japanese columns line up as English ones do.
pub fn pad(s: &str, width: usize) -> String {
    let columns: usize =
        s.chars().map(|c| if ('\u{1100}'..='\u{ffdc}').contains(&c) && !('\u{2000}'..='\u{2bff}').contains(&c) { 2 } else { 1 }).sum();
    format!("{s}{}", " ".repeat(width.saturating_sub(columns)))
}

/// The radiosity pass in numbers: patches, form factors and their time, and the residual of
/// each solver, iteration by iteration (the convergence chart as a table).
fn radiosity(scene: &Scene, s: &mut String, lang: Lang) {
    use crate::lesson::settings::Solver;
    let c = crate::effects::radiosity::convergence(scene, &Solver::ALL, None);
    let r = scene.spec.settings.radiosity;
    wln!(*s, "\n{}", lang.tr("Radiosity"));
    wln!(*s, "  {} {:>12}", pad(lang.tr("patches"), 40), c.patches);
    let reused = match (c.form_factors_cached, c.form_factors_reused) {
        (true, _) => lang.tr(" (computed by an earlier run, read from the on-disk cache)"),
        (false, true) => lang.tr(" (computed once in this run, then reused)"),
        (false, false) => "",
    };
    wln!(*s, "  {} {:>12}   {:.1} ms{reused}", pad(lang.tr("form factors (non-zero F_ij)"), 40), c.form_factors, c.form_factor_ms);
    let residual =
        format!("residual Σ A|E + ρFL − L| / Σ A L, per iteration (tolerance {}, at most {} iterations):", r.tolerance, r.iterations);
    wln!(*s, "  {}", lang.say(&residual));
    for (solver, sol, ms) in &c.runs {
        let shown: Vec<String> = sol.residuals.iter().take(12).map(|x| format!("{x:.1e}")).collect();
        let more = if sol.residuals.len() > 12 { format!(" … {:.1e}", sol.residual()) } else { String::new() };
        let mark = if *solver == r.solver { lang.tr(" (used)") } else { "" };
        let iterations = lang.say(&format!("{} iterations", sol.iterations));
        wln!(*s, "    {:<13} {:>15}, {ms:>8.1} ms{mark}: {}{more}", solver.name(), iterations, shown.join(" "));
    }
}

/// The render's counts, in pipeline order, for `explain`.
fn counts(st: &crate::render::RenderStats) -> Vec<(&'static str, u64)> {
    let r = &st.raster;
    vec![
        ("triangles in", r.triangles_in),
        ("  clipped (near plane or guard band)", r.triangles_clipped),
        ("  culled (back-facing)", r.triangles_culled),
        ("  outside the image", r.triangles_outside),
        ("  degenerate (zero area)", r.triangles_degenerate),
        ("samples rasterized (with overdraw)", r.samples_rasterized),
        ("samples shaded (visible, once each)", st.samples_shaded),
        ("vertices lit (Gouraud)", st.vertices_lit),
        ("faces lit (flat)", st.faces_lit),
        ("light evaluations", st.light_evaluations),
        ("  of them per sample (Phong)", st.light_evaluations_per_sample),
        ("diffuse-term evaluations", st.diffuse_evaluations),
        ("specular-term evaluations", st.specular_evaluations),
        ("NaN samples (replaced by 0)", st.nan_samples),
    ]
    .into_iter()
    // Each optional pass's labelled counts, in the order they were counted.
    .chain(st.counters.iter())
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two English words in a row (lower-case letters only, split at spaces): prose, not notation.
    fn english_prose(s: &str) -> Option<String> {
        let words: Vec<&str> = s.split(' ').collect();
        words.windows(2).find(|w| w.iter().all(|t| t.len() >= 2 && t.chars().all(|c| c.is_ascii_lowercase()))).map(|w| w.join(" "))
    }

    #[test]
    fn every_decision_of_every_lesson_reads_in_japanese() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
        let mut paths: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
        paths.retain(|p| p.extension().is_some_and(|e| e == "toml"));
        paths.sort();
        assert!(paths.len() >= 30, "the lessons are found");
        let (run, skip) = (Lang::Ja.tr("runs"), Lang::Ja.tr("skipped"));
        let mut decisions = 0;
        for path in paths {
            let lesson = crate::lesson::load(&path, &[]).unwrap();
            let scene = crate::scene::build::build(&lesson).unwrap();
            for line in text(&scene, false, Lang::Ja).lines() {
                if !line.contains(&format!(" {run} ")) && !line.contains(&format!(" {skip} ")) {
                    continue;
                }
                decisions += 1;
                // Material names are the user's; the rest is translated or notation.
                let words = scene.materials.iter().fold(line.to_string(), |l, m| l.replace(&m.name, ""));
                assert!(english_prose(&words).is_none(), "{}: untranslated {:?} in\n{line}", path.display(), english_prose(&words));
            }
        }
        assert!(decisions > 500, "{decisions} decisions checked");
        // The check itself can fail: an English reason is prose.
        assert!(english_prose("  頂点処理  実行  no light casts shadows by ray").is_some());
    }
}
