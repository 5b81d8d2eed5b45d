//! Whole figures kept in the on-disk cache ([`crate::cache`]) across runs: a second
//! `figures` of an unchanged lesson reads each picture back instead of drawing it again.
//!
//! The key is everything a figure is drawn from: the program, the validated lesson with its
//! text, overrides and language (a figure's cells re-validate the text), the bytes of every
//! file it reads, the figure's table and the drawing options. A figure that shows times (a
//! cost figure's timings, `--timings`) is a measurement, not a pure result: its key adds
//! the machine it was timed on (the CPU model and the threads), so another machine or
//! thread count times it again, and [`retime`] times it again on this one.

use super::{Figure, FigureError, FigureOptions};
use crate::cache::{self, Reader};
use crate::lesson::{FigureSpec, Lesson};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use web_time::Instant;

/// Set by `--retime`: figures that show times are timed again (and kept anew).
static RETIME: AtomicBool = AtomicBool::new(false);
/// Figures read whole from the cache in this process.
static READ: AtomicU64 = AtomicU64::new(0);

/// Times figures that show times again instead of reading them from the cache (`--retime`).
pub fn retime(on: bool) {
    RETIME.store(on, Ordering::Relaxed);
}

/// How many figures this process read whole from the cache.
pub fn read() -> u64 {
    READ.load(Ordering::Relaxed)
}

/// The first byte of a payload: its format.
const FORMAT: u8 = 1;

/// The figure `draw` makes, read from the cache when this program drew the same figure of
/// the same lesson the same way before (`timed`: it shows times, which are only reused on
/// the machine that measured them).
///
/// # Errors
/// `draw`'s.
pub(super) fn figure(
    base: &Lesson,
    spec: &FigureSpec,
    opts: &FigureOptions,
    timed: bool,
    draw: impl FnOnce() -> Result<Figure, FigureError>,
) -> Result<Figure, FigureError> {
    let key = cache::dir().and_then(|_| key(base, spec, opts, timed));
    // With the text log on, the figure is drawn: the log holds what a drawing draws.
    let retimed = timed && RETIME.load(Ordering::Relaxed);
    let read = !(super::text::logging_text() || retimed);
    if let Some(fig) = key.as_ref().filter(|_| read).and_then(cache::get).and_then(|b| from_bytes(&b)) {
        READ.fetch_add(1, Ordering::Relaxed);
        return Ok(fig);
    }
    let start = Instant::now();
    let fig = draw()?;
    if let Some(key) = key
        && start.elapsed().as_secs_f64() * 1e3 >= cache::MIN_KEPT_MS
        && let Some(bytes) = to_bytes(&fig)
    {
        cache::put(&key, &bytes);
    }
    Ok(fig)
}

/// The figure's key; `None` when a file it reads cannot be read.
fn key(base: &Lesson, spec: &FigureSpec, opts: &FigureOptions, timed: bool) -> Option<cache::Key> {
    let mut k = base.cache_key("figure")?;
    let sets: Vec<&str> = base.overrides.iter().map(|o| o.arg.as_str()).collect();
    k.part(format!("{:?}", (&base.source, sets, &base.title, base.lang, spec, opts)).as_bytes());
    if timed {
        k.part(crate::cost::timing::machine().as_bytes());
    }
    Some(k.finish())
}

/// The payload: the counts the command prints, the missing glyphs and the image as PNG.
fn to_bytes(fig: &Figure) -> Option<Vec<u8>> {
    let mut b = vec![FORMAT];
    for n in [fig.rasterizations, fig.cached, fig.missing_glyphs.len()] {
        b.extend(u32::try_from(n).ok()?.to_le_bytes());
    }
    fig.missing_glyphs.iter().for_each(|c| b.extend(u32::from(*c).to_le_bytes()));
    crate::output::encode_png_tagged(&mut b, fig.image.dimensions(), fig.image.as_raw(), true, &[]).ok()?;
    Some(b)
}

/// The figure of a payload; `None` when it is not one (then it is drawn again).
fn from_bytes(b: &[u8]) -> Option<Figure> {
    let mut r = Reader::new(b);
    if r.u8()? != FORMAT {
        return None;
    }
    let rasterizations = r.u32()? as usize;
    let cached = r.u32()? as usize;
    let glyphs = r.u32()? as usize;
    let missing_glyphs = (0..glyphs).map(|_| r.u32().and_then(char::from_u32)).collect::<Option<Vec<char>>>()?;
    let png = r.take(b.len() - (1 + 12 + 4 * glyphs))?;
    let image = image::load_from_memory_with_format(png, image::ImageFormat::Png).ok()?.into_rgba8();
    Some(Figure { image, stats: Default::default(), rasterizations, cached, missing_glyphs, kept: true })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_figure_survives_its_bytes_and_a_damaged_payload_is_refused() {
        let mut image = image::RgbaImage::new(3, 2);
        image.put_pixel(1, 1, image::Rgba([10, 200, 30, 128]));
        let fig = Figure { image, stats: Default::default(), rasterizations: 4, cached: 2, missing_glyphs: vec!['☃'], kept: false };
        let b = to_bytes(&fig).unwrap();
        let back = from_bytes(&b).unwrap();
        assert_eq!((back.image.as_raw(), back.rasterizations, back.cached), (fig.image.as_raw(), 4, 2));
        assert_eq!(back.missing_glyphs, ['☃']);
        assert!(back.kept);
        let mut other = b.clone();
        other[0] = FORMAT + 1;
        assert!(from_bytes(&other).is_none());
        assert!(from_bytes(&b[..b.len() - 9]).is_none());
    }
}
