//! `shadelab explain`: the equation each material uses, with its values, and the render plan.

use super::CliError;
use crate::render::plan::{Decision, plan};
use crate::scene::{ClassicModel, Material};
use glam::Vec3;
use std::path::PathBuf;

/// Arguments of `shadelab explain`.
#[derive(Debug, clap::Args)]
pub struct ExplainArgs {
    /// The lesson file.
    #[arg(value_name = "LESSON")]
    pub lesson: PathBuf,
    /// Override a value by dotted path (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
}

/// A colour as a person writes it: `0.5` for a grey, `[0.7, 0.04, 0.03]` otherwise.
fn show(c: Vec3) -> String {
    let f = |x: f32| format!("{}", (x * 1e4).round() / 1e4);
    if c.x == c.y && c.y == c.z { f(c.x) } else { format!("[{}, {}, {}]", f(c.x), f(c.y), f(c.z)) }
}

/// The course equation of a classic material, symbolic and with its values.
fn equation(m: &Material, global: Vec3) -> (String, String) {
    if let Some(brdf) = &m.physical {
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
    let spec = match m.model {
        ClassicModel::Lambert => ("", String::new()),
        ClassicModel::Phong => {
            (" + max(R·V, 0)^K_shi K_spec⊗L_spec", format!(" + max(R·V, 0)^{} {}⊗L_spec", m.shininess, show(m.specular)))
        }
        ClassicModel::BlinnPhong => {
            (" + max(N·H, 0)^K_shi K_spec⊗L_spec", format!(" + max(N·H, 0)^{} {}⊗L_spec", m.shininess, show(m.specular)))
        }
    };
    let symbolic = format!("I = L_glob⊗K_amb + L_emi + Σ_k C_spot^k {{ K_amb⊗L_amb^k + d^k (max(N·L, 0) K_diff⊗L_diff{}) }}", spec.0);
    let values = format!(
        "  = {}⊗{} + {} + Σ_k C_spot^k {{ {}⊗L_amb^k + d^k (max(N·L, 0) {}⊗L_diff{}) }}",
        show(global),
        show(m.ambient),
        show(m.emission),
        show(m.ambient),
        show(m.diffuse),
        spec.1
    );
    (symbolic, values)
}

fn line(d: &Decision) -> String {
    format!("  {:<24} {:<8} {}", d.what, if d.runs { "runs" } else { "skipped" }, d.why)
}

/// Prints the materials' equations and the plan.
pub fn run(args: ExplainArgs) -> Result<(), CliError> {
    let sets = super::overrides(&args.sets, Vec::new())?;
    let lesson = crate::lesson::load(&args.lesson, &sets)?;
    let scene = crate::scene::build::build(&lesson)?;
    let p = plan(&scene);
    outln!("{} ({})\n", lesson.title, args.lesson.display())?;
    outln!("Materials")?;
    for (m, terms) in scene.materials.iter().zip(&p.terms) {
        let (symbolic, values) = equation(m, scene.ambient);
        let model = if m.physical.is_some() { "physically based" } else { m.model.name() };
        outln!("  {} ({model})", m.name)?;
        outln!("    {symbolic}")?;
        outln!("    {values}")?;
        for t in terms {
            outln!("  {}", line(t))?;
        }
        outln!()?;
    }
    outln!("Lights")?;
    if p.lights.is_empty() {
        outln!("  (none)")?;
    }
    for d in &p.lights {
        outln!("{}", line(d))?;
    }
    outln!("\nPasses")?;
    for d in &p.passes {
        outln!("{}", line(d))?;
    }
    Ok(())
}
