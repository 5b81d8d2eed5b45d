//! Frames kept in the on-disk cache ([`crate::cache`]) across runs: a reference or a
//! figure's cell, keyed by the lesson it was rendered from and how.

use super::frame::Frame;
use crate::lesson::Lesson;
use web_time::Instant;

/// The frame `compute` renders from `lesson`, read from the cache when a run of this very
/// program already rendered it with the same inputs (`kind` and `extra` say what was
/// rendered and how: layers, samples, anything outside the lesson). True when it came from
/// the cache. Without a cache (or with an asset that cannot be read) it simply computes.
///
/// # Errors
/// `compute`'s.
pub fn frame<E>(
    lesson: &Lesson,
    kind: &'static str,
    extra: &[&[u8]],
    compute: impl FnOnce() -> Result<Frame, E>,
) -> Result<(Frame, bool), E> {
    let key = crate::cache::dir().and_then(|_| lesson.cache_key(kind)).map(|mut k| {
        extra.iter().for_each(|e| {
            k.part(e);
        });
        k.finish()
    });
    if let Some(frame) = key.as_ref().and_then(crate::cache::get).and_then(|b| Frame::from_bytes(&b)) {
        return Ok((frame, true));
    }
    let start = Instant::now();
    let frame = compute()?;
    if let Some(key) = key
        && start.elapsed().as_secs_f64() * 1e3 >= crate::cache::MIN_KEPT_MS
    {
        crate::cache::put(&key, &frame.to_bytes());
    }
    Ok((frame, false))
}

/// The bytes of a list of layers, as an `extra` part of a key.
pub fn layers_part(layers: &[super::Layer]) -> Vec<u8> {
    layers.iter().map(|l| l.name()).collect::<Vec<_>>().join(",").into_bytes()
}
