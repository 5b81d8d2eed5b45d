//! `shadelab bench`: speed of fixed workloads, as a table or JSON.
//!
//! `median_ms` (and min, max, Mpix/s) is render + develop to the 8-bit sRGB image, the
//! figure comparable to a GPU-style peer's clear + draw + readback; see [`crate::bench`].

use super::CliError;
use crate::bench::{BenchResult, WORKLOADS, run};

/// Arguments of `shadelab bench` (the global `--threads` sets the worker count).
#[derive(Debug, clap::Args)]
#[command(after_help = "Examples:
  One workload, the table:
    shadelab bench --workload sphere
  One thread, fewer frames, one JSON object per workload:
    shadelab --threads 1 bench --workload sphere-gouraud --frames 5 --format jsonl

Columns: `8-bit` median/min/max is the image a user gets, rendered and developed to 8-bit \
sRGB in one fused pass (`render -o x.png`); `float` is the other path, a linear float frame \
(`render -o x.exr`, layers, figures), not a part of the 8-bit time; `+png` is the 8-bit path \
plus PNG encoding in memory. See docs/performance.md.")]
pub struct BenchArgs {
    /// Run only this workload (sphere, sphere-gouraud, dense, slide, shadow, shadow-ray, bvh-build, path); default: all.
    #[arg(long, value_name = "NAME")]
    pub workload: Vec<String>,
    /// Timed frames per measurement (after warm-up frames).
    #[arg(long, default_value_t = 20, value_name = "N")]
    pub frames: usize,
    /// Untimed warm-up frames.
    #[arg(long, default_value_t = 3, value_name = "N")]
    pub warmup: usize,
    /// Text format of the results on stdout.
    #[arg(long, value_enum, default_value = "table")]
    pub format: BenchFormat,
}

/// `--format` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum BenchFormat {
    /// A table for people.
    Table,
    /// JSON Lines: one JSON object per workload, one per line (`json` is an old name of it).
    #[value(alias = "json")]
    Jsonl,
}

fn json(r: &BenchResult) -> String {
    format!(
        "{{\"workload\":\"{}\",\"median_ms\":{:.3},\"min_ms\":{:.3},\"max_ms\":{:.3},\"float_frame_median_ms\":{:.3},\"png_median_ms\":{:.3},\"frames\":{},\"threads\":{},\"pixels\":{},\"triangles\":{},\"mpix_per_s\":{:.2},\"mtri_per_s\":{:.2},\"peak_rss_mb\":{},\"shadow_rays\":{},\"bvh_build_ms\":{},\"paths\":{},\"path_rays\":{},\"mpaths_per_s\":{:.3},\"trace\":{}}}",
        r.workload.name,
        r.image.median_ms,
        r.image.min_ms,
        r.image.max_ms,
        r.render.median_ms,
        r.with_png.median_ms,
        r.image.runs,
        r.threads,
        r.pixels,
        r.triangles,
        r.mpix_per_s(),
        r.mtri_per_s(),
        r.peak_rss_mb.map_or("null".to_string(), |m| format!("{m:.1}")),
        r.shadow_rays,
        r.bvh_build.map_or("null".to_string(), |t| format!("{:.3}", t.median_ms)),
        r.paths,
        r.path_rays,
        r.mpaths_per_s(),
        r.trace.map_or("null".to_string(), |t| format!(
            "{{\"rays\":{},\"occluded\":{},\"single_median_ms\":{:.3},\"packet_median_ms\":{:.3},\"single_mrays_per_s\":{:.2},\"packet_mrays_per_s\":{:.2}}}",
            t.rays,
            t.occluded,
            t.single.median_ms,
            t.packet.median_ms,
            t.single_mrays(),
            t.packet_mrays()
        ))
    )
}

/// Runs the chosen workloads and prints the results.
pub fn run_bench(args: BenchArgs, quiet: bool) -> Result<(), CliError> {
    if args.frames == 0 || args.frames > 10_000 {
        return Err(CliError::Input(format!("--frames {}: give 1 to 10000", args.frames)));
    }
    let chosen: Vec<_> = if args.workload.is_empty() {
        WORKLOADS.to_vec()
    } else {
        args.workload
            .iter()
            .map(|n| {
                WORKLOADS.iter().find(|w| w.name == n).copied().ok_or_else(|| {
                    let names: Vec<&str> = WORKLOADS.iter().map(|w| w.name).collect();
                    CliError::Input(format!("--workload {n}: unknown (workloads: {})", names.join(", ")))
                })
            })
            .collect::<Result<_, _>>()?
    };
    if args.format == BenchFormat::Table && !quiet {
        outln!(
            "{} frames after {} warm-up frames, {} threads; times per frame in ms\n\
             8-bit: the image, rendered and developed to 8-bit sRGB in one fused pass (what `render -o x.png` does)\n\
             float: the other path, a linear float frame (EXR, layers, figures); not a part of 8-bit, often longer\n\
             +png: the 8-bit path plus PNG encoding in memory\n",
            args.frames,
            args.warmup,
            rayon::current_num_threads()
        )?;
        outln!(
            "{:<15} {:>9} {:>9} {:>9} {:>10} {:>10} {:>9} {:>9} {:>8}  workload",
            "name",
            "8-bit med",
            "8-bit min",
            "8-bit max",
            "float med",
            "+png med",
            "Mpix/s",
            "Mtri/s",
            "peak MB"
        )?;
    }
    for w in &chosen {
        let r = run(w, args.warmup, args.frames);
        if quiet {
            continue;
        }
        match args.format {
            BenchFormat::Jsonl => outln!("{}", json(&r))?,
            BenchFormat::Table => outln!(
                "{:<15} {:>9.2} {:>9.2} {:>9.2} {:>10.2} {:>10.2} {:>9.1} {:>9.2} {:>8}  {}",
                w.name,
                r.image.median_ms,
                r.image.min_ms,
                r.image.max_ms,
                r.render.median_ms,
                r.with_png.median_ms,
                r.mpix_per_s(),
                r.mtri_per_s(),
                r.peak_rss_mb.map_or("-".to_string(), |m| format!("{m:.0}")),
                w.description
            )?,
        }
        if args.format == BenchFormat::Table && r.shadow_rays > 0 {
            outln!(
                "{:<15} {} shadow rays a frame: {:.1} Mrays/s over the whole render; BVH build {:.2} ms (median)",
                "",
                r.shadow_rays,
                r.mrays_per_s(),
                r.bvh_build.map_or(f64::NAN, |t| t.median_ms)
            )?;
        }
        if args.format == BenchFormat::Table && r.paths > 0 {
            let threads = r.threads.max(1) as f64;
            outln!(
                "{:<15} {} paths, {} rays a frame (segments + next-event rays): {:.2} Mpaths/s, {:.1} Mrays/s; per thread {:.2} Mpaths/s, {:.1} Mrays/s",
                "",
                r.paths,
                r.path_rays,
                r.mpaths_per_s(),
                r.mpath_rays_per_s(),
                r.mpaths_per_s() / threads,
                r.mpath_rays_per_s() / threads
            )?;
        }
        if let (BenchFormat::Table, Some(t)) = (args.format, r.trace) {
            outln!(
                "{:<15} the rays alone ({} from the camera's hits, {} blocked): one at a time {:.2} ms, {:.1} Mrays/s; packets of 16 {:.2} ms, {:.1} Mrays/s (medians)",
                "",
                t.rays,
                t.occluded,
                t.single.median_ms,
                t.single_mrays(),
                t.packet.median_ms,
                t.packet_mrays()
            )?;
        }
    }
    Ok(())
}
