//! `shadelab envmap`: an environment image in another layout — latitude-longitude, cube
//! cross or mirror ball — for `[environment]`'s three ways of reading one.

use super::CliError;
use crate::scene::env_layout::{self, Layout};
use std::path::PathBuf;

/// The layouts `--to` names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum LayoutArg {
    /// Latitude-longitude (equirectangular), 2N × N: `kind = "latlong"`.
    Latlong,
    /// A horizontal cube cross, 4N × 3N: `kind = "cube"` with `cross`.
    Cross,
    /// A mirror ball (sphere map), N × N: `kind = "mirror_ball"`.
    #[value(name = "mirror_ball")]
    MirrorBall,
}

impl From<LayoutArg> for Layout {
    fn from(a: LayoutArg) -> Layout {
        match a {
            LayoutArg::Latlong => Layout::LatLong,
            LayoutArg::Cross => Layout::Cross,
            LayoutArg::MirrorBall => Layout::MirrorBall,
        }
    }
}

/// Arguments of `shadelab envmap`.
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  A lat-long HDRI as a cube cross (read it with [environment] kind = \"cube\", cross = \"studio-cross.hdr\"):
    shadelab envmap lessons/hdri/studio_small_03_1k.hdr --to cross -o studio-cross.hdr
  The same as a mirror ball, 512 pixels across, to compare with a photographed light probe:
    shadelab envmap lessons/hdri/studio_small_03_1k.hdr --to mirror_ball --size 512 -o studio-ball.exr
  A mirror-ball photograph back to a lat-long map:
    shadelab envmap studio-ball.exr --to latlong -o studio-latlong.hdr")]
pub struct EnvmapArgs {
    /// The image: a lat-long map (2:1), a cube cross (4:3) or a mirror ball (square), told
    /// apart by its shape; Radiance .hdr and OpenEXR are linear, PNG and JPEG sRGB.
    #[arg(value_name = "IMAGE")]
    pub input: PathBuf,
    /// The layout to write.
    #[arg(long, value_enum)]
    pub to: LayoutArg,
    /// N of the output: the lat-long map's height, the cross's face, the ball's side [default: about the input's detail].
    #[arg(long, value_name = "N")]
    pub size: Option<u32>,
    /// The image to write: .hdr or .exr (linear radiance), or .png (sRGB, 8-bit, clipped at 1).
    #[arg(short, long, value_name = "FILE")]
    pub output: PathBuf,
}

/// The largest N `--size` takes (a 4N-wide cross stays within the environment limit).
const MAX_N: u32 = crate::lesson::limits::MAX_ENV_SIDE / 4;

/// Reads the image, converts it through the lat-long map and writes it.
pub fn run(args: EnvmapArgs, quiet: bool) -> Result<(), CliError> {
    let ext = args.output.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
    let Some(ext) = ext.filter(|e| ["hdr", "exr", "png"].contains(&e.as_str())) else {
        return Err(CliError::Input(format!(
            "-o {}: `envmap` writes .hdr, .exr or .png\n  hint: name it {}",
            args.output.display(),
            args.output.with_extension("hdr").display()
        )));
    };
    if let Some(n) = args.size
        && !(2..=MAX_N).contains(&n)
    {
        return Err(CliError::Input(format!("--size {n}: give 2 to {MAX_N}")));
    }
    let input = args.input.display();
    if !args.input.is_file() {
        return Err(CliError::Input(format!("{input}: no such file\n  hint: give an image file (.hdr, .exr, .png or .jpg)")));
    }
    let (w, h, texels) = crate::scene::environment::decode_rgb(&args.input).map_err(|e| CliError::Input(format!("{input}: {e}")))?;
    let Some(from) = Layout::of_shape(w, h) else {
        return Err(CliError::Input(format!(
            "{input}: {w}×{h} is none of the layouts\n  hint: a lat-long map is 2:1, a cube cross 4:3 (4N × 3N), a mirror ball square"
        )));
    };
    let to = Layout::from(args.to);
    let n = args.size.unwrap_or_else(|| to.matching_n(from, from.n_of(w)).min(MAX_N));
    let env = env_layout::to_latlong(from, w, h, texels).map_err(|e| CliError::Input(format!("{input}: {e}")))?;
    let (ow, oh, out) = env_layout::from_latlong(&env, to, n);
    match ext.as_str() {
        "png" => {
            let rgb: Vec<u8> = out.iter().flat_map(|c| c.to_array()).map(crate::render::srgb::encode_u8).collect();
            crate::output::write_png(&args.output, ow, oh, &rgb)?;
        }
        "hdr" => crate::output::write_hdr(&args.output, ow, oh, &out)?,
        _ => crate::output::write_exr(&args.output, ow, oh, &out)?,
    }
    if !quiet {
        outln!(
            "wrote {} ({ow}×{oh}, {} from a {w}×{h} {})\n  next: [environment] {}",
            args.output.display(),
            to.name(),
            from.name(),
            match to {
                Layout::LatLong => format!("kind = \"latlong\", map = \"{}\"", args.output.display()),
                Layout::Cross => format!("kind = \"cube\", cross = \"{}\"", args.output.display()),
                Layout::MirrorBall => format!("kind = \"mirror_ball\", map = \"{}\"", args.output.display()),
            }
        )?;
    }
    Ok(())
}
