//! `shadelab brdf`: evaluate a material's BRDF, plot its lobe, measure its albedo.

use super::CliError;
use crate::figure::charts::{LobeOptions, Plotted, albedo_chart, lobe_chart_of};
use crate::shading::brdf::{Brdf, directional_albedo};
use crate::shading::cook_torrance::Terms;
use glam::Vec3;
use std::io::Read;
use std::path::{Path, PathBuf};

/// Arguments of `shadelab brdf`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  The GGX and Beckmann lobes at 30° and 60° incidence (lobe.png and lobe.svg):
    shadelab brdf lobe lessons/09-microfacet-ndfs.toml --material GGX,Beckmann --incidence 30,60 -o out/lobe.png
  How much light a rough GGX surface returns (white furnace), as CSV:
    shadelab brdf albedo lessons/14-energy.toml --material 'GGX r = 1 (α = 1)' --cos 1,0.5,0.1 --format csv
  One BRDF value, l along the normal and v 37° off it:
    echo 0,0,1,0.6,0,0.8 | shadelab brdf eval lessons/09-microfacet-ndfs.toml --material GGX")]
pub struct BrdfArgs {
    /// What to do.
    #[command(subcommand)]
    pub action: BrdfAction,
}

/// `shadelab brdf` subcommands.
#[derive(Debug, clap::Subcommand)]
pub enum BrdfAction {
    /// Read `lx,ly,lz,vx,vy,vz` lines (local frame, z = normal) on stdin; print `f_r,f_g,f_b` (1/sr, cosine NOT included).
    ///
    /// Blank lines are skipped, and the first line may be a header of words (`lx,ly,lz,vx,vy,vz`).
    /// All input is read and checked first: a line that is not 6 finite numbers is an error
    /// (`stdin:LINE: ...`, exit 2) and nothing is printed.
    #[command(after_help = "Examples:
  One value, l along the normal and v 37° off it:
    echo 0,0,1,0.6,0,0.8 | shadelab brdf eval lessons/09-microfacet-ndfs.toml --material GGX
  A batch with a header line, from a file:
    printf 'lx,ly,lz,vx,vy,vz\\n0,0,1,0,0,1\\n0.6,0,0.8,-0.6,0,0.8\\n' > dirs.csv
    shadelab brdf eval lessons/09-microfacet-ndfs.toml --material Beckmann < dirs.csv")]
    Eval {
        /// The lesson file.
        lesson: PathBuf,
        /// The material's name.
        #[arg(long)]
        material: String,
    },
    /// Polar plot in the plane of incidence, written as PNG and SVG: f·cos θ_o of physically
    /// based materials, the course's I(θ_o) for a unit light of classic ones (`phong`,
    /// `blinn_phong`, `lambert`; no normalization).
    #[command(after_help = "Examples:
  Two NDFs at two angles of incidence (lobe.png and lobe.svg):
    shadelab brdf lobe lessons/09-microfacet-ndfs.toml --material GGX,Beckmann --incidence 30,60 -o out/lobe.png
  A classic lobe with l and v exchanged (reciprocity):
    shadelab brdf lobe lessons/20-lobes-and-reciprocity.toml --material 'Phong K_shi = 20' --incidence 30 --swap -o out/swap.png")]
    Lobe {
        /// The lesson file.
        lesson: PathBuf,
        /// Material names, comma-separated.
        #[arg(long, value_delimiter = ',', required = true)]
        material: Vec<String>,
        /// Angles of incidence in degrees, comma-separated.
        #[arg(long, value_delimiter = ',', default_value = "30")]
        incidence: Vec<f64>,
        /// Also draw each lobe with l and v exchanged in f (a reciprocal BRDF draws the same curve).
        #[arg(long)]
        swap: bool,
        /// Cook-Torrance partial products to draw instead of the whole f, comma-separated:
        /// D, DG, DGF (cook_torrance materials only).
        #[arg(long, value_delimiter = ',', value_parser = parse_terms)]
        terms: Vec<Terms>,
        /// Output file, `NAME.png` or `NAME.svg`: the chart is written in both formats, the
        /// one named and the other beside it (`-o x.svg` writes x.svg and x.png).
        #[arg(short, long, default_value = "lobe.png", value_name = "FILE")]
        output: PathBuf,
    },
    /// Directional albedo against the angle of incidence (white furnace), as a chart or CSV.
    #[command(after_help = "Examples:
  The chart (albedo.png and albedo.svg in out/):
    shadelab brdf albedo lessons/14-energy.toml --material 'GGX r = 1 (α = 1)' -o out/albedo.png
  The values at three angles, as CSV on stdout:
    shadelab brdf albedo lessons/14-energy.toml --material 'GGX r = 1 (α = 1)' --cos 1,0.5,0.1 --format csv")]
    Albedo {
        /// The lesson file.
        lesson: PathBuf,
        /// Material names, comma-separated.
        #[arg(long, value_delimiter = ',', required = true)]
        material: Vec<String>,
        /// Evaluate at these cos θ (with --format csv) [default: 1,0.75,0.5,0.25,0.1].
        #[arg(long, value_delimiter = ',')]
        cos: Vec<f64>,
        /// What to make: a chart (PNG + SVG files), or CSV values (`png` is an old name of `chart`).
        #[arg(long, value_enum, default_value = "chart")]
        format: AlbedoFormat,
        /// Output file. chart: `NAME.png` or `NAME.svg`, the chart in both formats, the one
        /// named and the other beside it [default: albedo.png]. csv: the CSV is written to
        /// FILE instead of stdout.
        #[arg(short, long, value_name = "FILE")]
        output: Option<PathBuf>,
        /// Gauss-Legendre nodes per panel and dimension (more: slower, tighter bound).
        #[arg(long, default_value_t = 6, value_name = "N")]
        samples: usize,
    },
}

/// `--format` of `brdf albedo`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum AlbedoFormat {
    /// A chart, written as PNG + SVG files.
    #[value(alias = "png")]
    Chart,
    /// `material,cos_theta,albedo,error_bound` lines, on stdout or to `-o FILE`.
    Csv,
}

/// The BRDF of a named, physically based material of a lesson.
fn brdf_of(lesson: &Path, name: &str) -> Result<Brdf, CliError> {
    let l = crate::lesson::load(lesson, &[])?;
    let names: Vec<&str> = l.materials.iter().map(|m| m.name.as_str()).collect();
    let m = l.materials.iter().find(|m| m.name == name).ok_or_else(|| {
        let physical: Vec<&str> = l.materials.iter().filter(|m| m.brdf().is_some()).map(|m| m.name.as_str()).collect();
        let hint = match crate::lesson::suggest(name, &names) {
            Some(s) => format!("did you mean `{s}`? Physically based materials: {}", physical.join(", ")),
            None => format!("physically based materials: {}", physical.join(", ")),
        };
        CliError::Input(format!("{}: no material named `{name}`\n  hint: {hint}", lesson.display()))
    })?;
    m.brdf().copied().ok_or_else(|| {
        CliError::Input(format!(
            "{}: `{name}` is a classic material ({}), not a BRDF: the classic models have no π and no units; use a physically based model such as `normalized_phong` or `cook_torrance`",
            lesson.display(),
            m.family_name()
        ))
    })
}

/// A `--terms` value: `D`, `DG` or `DGF`.
fn parse_terms(s: &str) -> Result<Terms, String> {
    Terms::ALL.into_iter().find(|t| t.name() == s).ok_or_else(|| format!("`{s}`: give D, DG or DGF"))
}

/// A named material of a lesson as a lobe chart plots it: physically based or classic.
fn plotted_of(lesson: &Path, name: &str) -> Result<Plotted, CliError> {
    let l = crate::lesson::load(lesson, &[])?;
    match l.materials.iter().find(|m| m.name == name) {
        Some(m) => Ok(match (m.brdf(), m.classic()) {
            (Some(b), _) => Plotted::Brdf(*b),
            (None, Some(c)) => Plotted::Classic(*c),
            (None, None) => unreachable!("a material is physically based or classic"),
        }),
        None => {
            let names: Vec<&str> = l.materials.iter().map(|m| m.name.as_str()).collect();
            let hint = match crate::lesson::suggest(name, &names) {
                Some(s) => format!("did you mean `{s}`? Materials: {}", names.join(", ")),
                None => format!("materials: {}", names.join(", ")),
            };
            Err(CliError::Input(format!("{}: no material named `{name}`\n  hint: {hint}", lesson.display())))
        }
    }
}

/// Runs a `brdf` subcommand.
pub fn run(args: BrdfArgs, quiet: bool) -> Result<(), CliError> {
    match args.action {
        BrdfAction::Eval { lesson, material } => eval(&lesson, &material, quiet),
        BrdfAction::Lobe { lesson, material, incidence, swap, terms, output } => {
            lobe(&lesson, &material, &incidence, LobeOptions { swap, terms, azimuth: Vec::new() }, &output, quiet)
        }
        BrdfAction::Albedo { lesson, material, cos, format, output, samples } => {
            albedo(&lesson, &material, &cos, format, output.as_deref(), samples, quiet)
        }
    }
}

/// `brdf eval`: every line of stdin is read and checked before anything is printed, so
/// a bad line gives an error and no partial batch.
fn eval(lesson: &Path, material: &str, quiet: bool) -> Result<(), CliError> {
    let brdf = brdf_of(lesson, material)?;
    let mut input = String::new();
    std::io::stdin().lock().read_to_string(&mut input).map_err(|e| CliError::Input(format!("stdin: {e}")))?;
    let mut out = String::from("f_r,f_g,f_b\n");
    for (l, v) in eval_directions(&input)? {
        let f = brdf.eval(l, v);
        out += &format!("{},{},{}\n", f.x, f.y, f.z);
    }
    // The values are the result; -q checks the input only.
    if quiet { Ok(()) } else { out!("{out}") }
}

/// The unit vector along finite `xyz`, normalized in f64 after dividing by the largest
/// magnitude (so 1e300 does not overflow and 1e-300 does not underflow); `None` only for
/// [0, 0, 0].
fn unit(xyz: &[f64]) -> Option<Vec3> {
    let big = xyz.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if big == 0.0 {
        return None;
    }
    let d = glam::DVec3::new(xyz[0] / big, xyz[1] / big, xyz[2] / big).normalize();
    Some(d.as_vec3())
}

/// The (l, v) pairs of `brdf eval`'s input: `lx,ly,lz,vx,vy,vz` lines, blank lines
/// skipped; the first line may be a header of six comma-separated words (each starting with
/// a letter and not a number), so a data line in another separator is an error, not a header.
fn eval_directions(input: &str) -> Result<Vec<(Vec3, Vec3)>, CliError> {
    let mut pairs = Vec::new();
    let mut first = true;
    for (i, line) in input.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        let fields: Vec<&str> = t.split(',').map(str::trim).collect();
        let is_header =
            first && fields.len() == 6 && fields.iter().all(|f| f.starts_with(|c: char| c.is_alphabetic()) && f.parse::<f64>().is_err());
        first = false;
        if is_header {
            continue;
        }
        let bad = |why: &str| {
            let shown: String = if t.chars().count() > 60 { t.chars().take(57).chain("...".chars()).collect() } else { t.to_string() };
            CliError::Input(format!(
                "stdin:{}: expected 6 numbers lx,ly,lz,vx,vy,vz, got `{shown}` ({why})\n  hint: one pair of directions per line in the local frame (z = normal), e.g. 0,0,1,0.6,0,0.8; only the first line may be a header such as lx,ly,lz,vx,vy,vz",
                i + 1
            ))
        };
        if fields.len() != 6 {
            return Err(bad(&format!("{} field{}", fields.len(), if fields.len() == 1 { "" } else { "s" })));
        }
        let mut n = [0f64; 6];
        for (k, f) in fields.iter().enumerate() {
            n[k] = match f.parse::<f64>() {
                Ok(x) if x.is_finite() => x,
                Ok(_) => return Err(bad(&format!("field {} is not finite", k + 1))),
                Err(_) => return Err(bad(&format!("field {} `{f}` is not a number", k + 1))),
            };
        }
        let (Some(l), Some(v)) = (unit(&n[..3]), unit(&n[3..])) else {
            return Err(CliError::Input(format!("stdin:{}: a direction is [0, 0, 0]\n  hint: l and v must have a length", i + 1)));
        };
        pairs.push((l, v));
    }
    Ok(pairs)
}

/// The PNG and SVG files of a chart named by `-o`: `x.png` or `x.svg`, the other beside it.
fn chart_paths(output: &Path) -> Result<(PathBuf, PathBuf), CliError> {
    match output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("png") => Ok((output.to_path_buf(), output.with_extension("svg"))),
        Some("svg") => Ok((output.with_extension("png"), output.to_path_buf())),
        _ => Err(CliError::Input(format!(
            "-o {}: a chart is written as PNG and SVG, so the name must end in .png or .svg\n  hint: e.g. -o {} (the .svg is written beside it)",
            output.display(),
            output.with_extension("png").display()
        ))),
    }
}

fn write_chart(output: &Path, chart: &crate::figure::plot::Chart, quiet: bool) -> Result<(), CliError> {
    let (png, svg) = chart_paths(output)?;
    crate::output::write_png(&png, chart.png.width(), chart.png.height(), chart.png.as_raw())?;
    crate::output::write_atomic(&svg, |w| w.write_all(chart.svg.as_bytes()).map_err(|e| e.to_string()))?;
    if quiet {
        return Ok(());
    }
    outln!("wrote {} and {}", png.display(), svg.display())
}

fn lobe(lesson: &Path, materials: &[String], incidence: &[f64], opts: LobeOptions, output: &Path, quiet: bool) -> Result<(), CliError> {
    chart_paths(output)?;
    if incidence.iter().any(|i| !i.is_finite() || !(0.0..90.0).contains(i)) {
        return Err(CliError::Input("--incidence: angles must be in [0, 90) degrees".into()));
    }
    let plotted: Vec<(String, Plotted)> =
        materials.iter().map(|n| plotted_of(lesson, n).map(|m| (n.clone(), m))).collect::<Result<_, _>>()?;
    if !opts.terms.is_empty()
        && let Some((name, _)) = plotted.iter().find(|(_, m)| !matches!(m, Plotted::Brdf(Brdf::CookTorrance(_))))
    {
        return Err(CliError::Input(format!(
            "--terms: `{name}` is not a cook_torrance material\n  hint: --terms splits the Cook-Torrance numerator D G F; drop it for other models"
        )));
    }
    let title = match plotted.iter().any(|(_, m)| matches!(m, Plotted::Classic(_))) {
        true => "Lobes in the plane of incidence: f·cos θo (BRDFs), I for a unit light (classic)",
        false => "BRDF lobe: f·cos θo in the plane of incidence",
    };
    let chart = lobe_chart_of(&plotted, incidence, &opts, title, crate::lesson::load(lesson, &[])?.lang).map_err(CliError::Internal)?;
    write_chart(output, &chart, quiet)
}

#[allow(clippy::too_many_arguments)]
fn albedo(
    lesson: &Path,
    materials: &[String],
    cos: &[f64],
    format: AlbedoFormat,
    output: Option<&Path>,
    samples: usize,
    quiet: bool,
) -> Result<(), CliError> {
    if cos.iter().any(|c| !c.is_finite() || *c <= 0.0 || *c > 1.0) {
        return Err(CliError::Input("--cos: values must be in (0, 1]".into()));
    }
    if !(1..=64).contains(&samples) {
        return Err(CliError::Input("--samples: give 1 to 64".into()));
    }
    if format == AlbedoFormat::Chart && !cos.is_empty() {
        return Err(CliError::Input(
            "--cos is read with --format csv only (the chart sweeps 0° to 88°)\n  hint: add --format csv, or drop --cos".into(),
        ));
    }
    match (format, output) {
        (AlbedoFormat::Chart, Some(o)) => {
            chart_paths(o)?;
        }
        (AlbedoFormat::Csv, Some(o)) if crate::output::Format::from_path(o).is_some() || o.extension().is_some_and(|e| e == "svg") => {
            return Err(CliError::Input(format!(
                "-o {}: --format csv writes text, and this name says image\n  hint: name the file e.g. {}",
                o.display(),
                o.with_extension("csv").display()
            )));
        }
        _ => {}
    }
    let brdfs: Vec<(String, Brdf)> = materials.iter().map(|n| brdf_of(lesson, n).map(|b| (n.clone(), b))).collect::<Result<_, _>>()?;
    if format == AlbedoFormat::Csv {
        let cos: Vec<f64> = if cos.is_empty() { vec![1.0, 0.75, 0.5, 0.25, 0.1] } else { cos.to_vec() };
        let mut text = String::from("material,cos_theta,albedo,error_bound\n");
        for (name, b) in &brdfs {
            for c in &cos {
                let (a, e) = directional_albedo(b, *c, samples);
                text += &format!("{name},{c},{a:.6},{e:.2e}\n");
            }
        }
        return match output {
            Some(o) => {
                crate::output::write_atomic(o, |w| w.write_all(text.as_bytes()).map_err(|e| e.to_string()))?;
                if quiet { Ok(()) } else { outln!("wrote {}", o.display()) }
            }
            None if quiet => Ok(()),
            None => out!("{text}"),
        };
    }
    let chart = albedo_chart(&brdfs, samples, "Directional albedo (white furnace)", crate::lesson::load(lesson, &[])?.lang)
        .map_err(CliError::Internal)?;
    write_chart(output.unwrap_or(Path::new("albedo.png")), &chart, quiet)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brdf_eval_reads_f64_and_normalizes_huge_values() {
        // In f32, 1e20 squared overflowed and the direction was called [0, 0, 0].
        let pairs = eval_directions("1e20,0,1e20,0,0,1\n1e150,0,0,0,1e-300,0\n").unwrap();
        let h = std::f32::consts::FRAC_1_SQRT_2;
        assert!((pairs[0].0 - Vec3::new(h, 0.0, h)).length() < 1e-7, "{:?}", pairs[0]);
        assert_eq!(pairs[0].1, Vec3::Z);
        assert_eq!(pairs[1], (Vec3::X, Vec3::Y));
        // Only an exact zero is zero; a non-finite number is still refused.
        let e = eval_directions("0,0,0,0,0,1\n").unwrap_err().to_string();
        assert!(e.contains("a direction is [0, 0, 0]"), "{e}");
        let e = eval_directions("1e400,0,0,0,0,1\n").unwrap_err().to_string();
        assert!(e.contains("field 1 is not finite"), "{e}");
    }
}
