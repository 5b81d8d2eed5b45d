//! `shadelab brdf`: evaluate a material's BRDF, plot its lobe, measure its albedo.

use super::CliError;
use crate::figure::charts::{albedo_chart, lobe_chart};
use crate::shading::brdf::{Brdf, directional_albedo};
use glam::Vec3;
use std::io::{BufRead, Write};
use std::path::{Path, PathBuf};

/// Arguments of `shadelab brdf`.
#[derive(Debug, clap::Args)]
pub struct BrdfArgs {
    /// What to do.
    #[command(subcommand)]
    pub action: BrdfAction,
}

/// `shadelab brdf` subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum BrdfAction {
    /// Read `lx,ly,lz,vx,vy,vz` lines (local frame, z = normal; header optional) on stdin; print `f_r,f_g,f_b` (1/sr, cosine NOT included).
    Eval {
        /// The lesson file.
        lesson: PathBuf,
        /// The material's name.
        #[arg(long)]
        material: String,
    },
    /// Polar plot of f·cos θ_o in the plane of incidence (PNG, and SVG beside it).
    Lobe {
        /// The lesson file.
        lesson: PathBuf,
        /// Material names, comma-separated.
        #[arg(long, value_delimiter = ',', required = true)]
        material: Vec<String>,
        /// Angles of incidence in degrees, comma-separated.
        #[arg(long, value_delimiter = ',', default_value = "30")]
        incidence: Vec<f64>,
        /// Output PNG (an SVG is written next to it).
        #[arg(short, long, default_value = "lobe.png")]
        output: PathBuf,
    },
    /// Directional albedo against the angle of incidence (white furnace), as a chart or CSV.
    Albedo {
        /// The lesson file.
        lesson: PathBuf,
        /// Material names, comma-separated.
        #[arg(long, value_delimiter = ',', required = true)]
        material: Vec<String>,
        /// Evaluate at these cos θ (CSV), instead of the chart's 0°–89° sweep.
        #[arg(long, value_delimiter = ',')]
        cos: Vec<f64>,
        /// Output format.
        #[arg(long, value_enum, default_value = "png")]
        format: AlbedoFormat,
        /// Output PNG (an SVG is written next to it).
        #[arg(short, long, default_value = "albedo.png")]
        output: PathBuf,
        /// Gauss-Legendre nodes per panel and dimension (more: slower, tighter bound).
        #[arg(long, default_value_t = 6)]
        samples: usize,
    },
}

/// `--format` of `brdf albedo`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum AlbedoFormat {
    /// A chart (PNG + SVG).
    Png,
    /// `material,cos_theta,albedo,error_bound` lines on stdout.
    Csv,
}

/// The BRDF of a named, physically based material of a lesson.
fn brdf_of(lesson: &Path, name: &str) -> Result<Brdf, CliError> {
    let l = crate::lesson::load(lesson, &[])?;
    let names: Vec<&str> = l.materials.iter().map(|m| m.name.as_str()).collect();
    let m =
        l.materials.iter().find(|m| m.name == name).ok_or_else(|| {
            CliError::Input(format!("{}: no material named `{name}` (materials: {})", lesson.display(), names.join(", ")))
        })?;
    m.physical.ok_or_else(|| {
        CliError::Input(format!(
            "{}: `{name}` is a classic material ({}), not a BRDF: the classic models have no π and no units; use a physically based model such as `normalized_phong` or `cook_torrance`",
            lesson.display(),
            m.model.name()
        ))
    })
}

/// Runs a `brdf` subcommand.
pub fn run(args: BrdfArgs) -> Result<(), CliError> {
    match args.action {
        BrdfAction::Eval { lesson, material } => eval(&lesson, &material),
        BrdfAction::Lobe { lesson, material, incidence, output } => lobe(&lesson, &material, &incidence, &output),
        BrdfAction::Albedo { lesson, material, cos, format, output, samples } => albedo(&lesson, &material, &cos, format, &output, samples),
    }
}

fn eval(lesson: &Path, material: &str) -> Result<(), CliError> {
    let brdf = brdf_of(lesson, material)?;
    let stdin = std::io::stdin();
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    let io = |e: std::io::Error| CliError::Internal(format!("stdout: {e}"));
    writeln!(out, "f_r,f_g,f_b").map_err(io)?;
    for (i, line) in stdin.lock().lines().enumerate() {
        let line = line.map_err(|e| CliError::Input(format!("stdin: {e}")))?;
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        let nums: Result<Vec<f32>, _> = t.split(',').map(|x| x.trim().parse::<f32>()).collect();
        let nums = match nums {
            Ok(n) if n.len() == 6 && n.iter().all(|x| x.is_finite()) => n,
            // A first line that is not numbers is a header.
            _ if i == 0 => continue,
            _ => return Err(CliError::Input(format!("stdin:{}: expected six finite numbers lx,ly,lz,vx,vy,vz, got `{t}`", i + 1))),
        };
        let (l, v) = (Vec3::new(nums[0], nums[1], nums[2]), Vec3::new(nums[3], nums[4], nums[5]));
        let (Some(l), Some(v)) = (l.try_normalize(), v.try_normalize()) else {
            return Err(CliError::Input(format!("stdin:{}: a direction is [0, 0, 0]", i + 1)));
        };
        let f = brdf.eval(l, v);
        writeln!(out, "{},{},{}", f.x, f.y, f.z).map_err(io)?;
    }
    Ok(())
}

fn write_chart(output: &Path, chart: &crate::figure::plot::Chart) -> Result<(), CliError> {
    crate::output::write_png(output, chart.png.width(), chart.png.height(), chart.png.as_raw())?;
    let svg = output.with_extension("svg");
    crate::output::write_atomic(&svg, |w| w.write_all(chart.svg.as_bytes()).map_err(|e| e.to_string()))?;
    println!("wrote {} and {}", output.display(), svg.display());
    Ok(())
}

fn lobe(lesson: &Path, materials: &[String], incidence: &[f64], output: &Path) -> Result<(), CliError> {
    if incidence.iter().any(|i| !i.is_finite() || !(0.0..90.0).contains(i)) {
        return Err(CliError::Input("--incidence: angles must be in [0, 90) degrees".into()));
    }
    let brdfs: Vec<(String, Brdf)> = materials.iter().map(|n| brdf_of(lesson, n).map(|b| (n.clone(), b))).collect::<Result<_, _>>()?;
    let chart = lobe_chart(&brdfs, incidence, "BRDF lobe: f·cos θo in the plane of incidence").map_err(CliError::Internal)?;
    write_chart(output, &chart)
}

fn albedo(lesson: &Path, materials: &[String], cos: &[f64], format: AlbedoFormat, output: &Path, samples: usize) -> Result<(), CliError> {
    if cos.iter().any(|c| !c.is_finite() || *c <= 0.0 || *c > 1.0) {
        return Err(CliError::Input("--cos: values must be in (0, 1]".into()));
    }
    if !(1..=64).contains(&samples) {
        return Err(CliError::Input("--samples: give 1 to 64".into()));
    }
    let brdfs: Vec<(String, Brdf)> = materials.iter().map(|n| brdf_of(lesson, n).map(|b| (n.clone(), b))).collect::<Result<_, _>>()?;
    if format == AlbedoFormat::Csv {
        let cos: Vec<f64> = if cos.is_empty() { vec![1.0, 0.75, 0.5, 0.25, 0.1] } else { cos.to_vec() };
        println!("material,cos_theta,albedo,error_bound");
        for (name, b) in &brdfs {
            for c in &cos {
                let (a, e) = directional_albedo(b, *c, samples);
                println!("{name},{c},{a:.6},{e:.2e}");
            }
        }
        return Ok(());
    }
    let chart = albedo_chart(&brdfs, samples, "Directional albedo (white furnace)").map_err(CliError::Internal)?;
    write_chart(output, &chart)
}
