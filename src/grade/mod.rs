//! Grading a student's lesson against a reference lesson, term by term.
//!
//! Both are rendered with the reference's supersampling; each term of the illumination
//! equation (the total, ambient, diffuse, specular, emission, reflection, transmission) is
//! developed with the reference's exposure and tone map and compared with ꟻLIP (Andersson
//! et al. 2020, [`crate::cost::flip`]) beside the mean and 95th-percentile error. Shadows are
//! compared as masks: where the direct light is less than half what it is with shadows off.
//! Points come from a [`rubric::Rubric`]; [`findings`] names what differs in words a student
//! understands. docs/grading.md has the metrics, the rubric and the findings.

pub mod findings;
pub mod report;
pub mod rubric;

use crate::lesson::settings::Tonemap;
use crate::lesson::{Lesson, LessonError, Override};
use crate::render::budget::OverBudget;
use crate::render::frame::Layer;
use crate::scene::build::SceneError;
use glam::Vec3;
use rubric::{Rubric, Term};

/// The terms compared image to image, in report order.
pub const IMAGE_TERMS: [Term; 7] =
    [Term::Total, Term::Ambient, Term::Diffuse, Term::Specular, Term::Emission, Term::Reflection, Term::Transmission];

/// A developed value this far above black (of 255) counts as showing the term.
const VISIBLE_CODE: u8 = 2;

/// Why a lesson could not be rendered for grading.
#[derive(Debug, thiserror::Error)]
pub enum GradeInputError {
    /// It does not validate.
    #[error("{0}")]
    Lesson(#[from] LessonError),
    /// A file it names cannot be used (or is outside its folder).
    #[error("{0}")]
    Scene(#[from] SceneError),
    /// Its render is over the budget.
    #[error("{0}")]
    Budget(#[from] OverBudget),
}

/// How both lessons' terms are developed: the reference's exposure and tone map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Develop {
    /// Exposure in stops.
    pub exposure: f32,
    /// Tone map.
    pub tonemap: Tonemap,
}

/// One lesson rendered for grading.
#[derive(Debug, Clone)]
pub struct Rendered {
    /// Width and height in pixels.
    pub size: (u32, u32),
    /// Per [`IMAGE_TERMS`] entry, the linear layer (over the background), row-major.
    pub linear: Vec<Vec<Vec3>>,
    /// Per [`IMAGE_TERMS`] entry, the developed 8-bit sRGB image (RGB, row-major).
    pub developed: Vec<Vec<u8>>,
    /// Luminance of the direct light (diffuse + specular) per pixel, with shadows.
    pub direct: Vec<f32>,
    /// The same with every shadow off.
    pub unshadowed: Vec<f32>,
}

/// Rec. 709 luminance (ITU-R BT.709, the sRGB primaries); 0 for a value that is not finite
/// (the developed image shows such a sample as black too).
pub fn luminance(c: Vec3) -> f32 {
    let l = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
    if l.is_finite() { l } else { 0.0 }
}

/// Renders `lesson`'s terms, and its direct light again with every shadow off.
///
/// # Errors
/// The lesson (with the shadows turned off) does not build, or is over the budget.
pub fn render(lesson: &Lesson, develop: Develop) -> Result<Rendered, GradeInputError> {
    let layers: Vec<Layer> = IMAGE_TERMS.iter().map(|t| t.layer().expect("image terms are layers")).collect();
    let scene = crate::scene::build::build(lesson)?;
    crate::render::budget::check(&scene).map_err(|e| e.at(lesson.path.display()))?;
    let (frame, _) = crate::render::render(&scene, &layers);
    let size = (frame.width, frame.height);
    let linear: Vec<Vec<Vec3>> = layers.iter().map(|&l| frame.layer(l).expect("the layers asked for are kept")).collect();
    let developed = layers
        .iter()
        .map(|&l| crate::render::develop::develop(&frame, l, develop.exposure, develop.tonemap).expect("the layers asked for are kept"))
        .collect();
    let direct_of = |linear: &[Vec<Vec3>]| -> Vec<f32> {
        let (d, s) = (&linear[2], &linear[3]);
        d.iter().zip(s).map(|(d, s)| luminance(*d + *s)).collect()
    };
    let direct = direct_of(&linear);
    // Shadows off: `[render] shadows` and every light that chose its own method.
    let mut sets = lesson.overrides.clone();
    let mut off = vec!["render.shadows=none".to_string()];
    off.extend(lesson.scene.lights.iter().enumerate().filter(|(_, l)| l.shadows.is_some()).map(|(i, _)| format!("light.{i}.shadows=none")));
    sets.extend(off.iter().map(|a| Override::parse(a).expect("a valid override")));
    let open = crate::lesson::parse(&lesson.source, &lesson.path, &sets)?;
    let open_scene = crate::scene::build::build(&open)?;
    let (open_frame, _) = crate::render::render(&open_scene, &[Layer::Diffuse, Layer::Specular]);
    let unshadowed_layers =
        vec![Vec::new(), Vec::new(), open_frame.layer(Layer::Diffuse).expect("kept"), open_frame.layer(Layer::Specular).expect("kept")];
    let unshadowed = direct_of(&unshadowed_layers);
    Ok(Rendered { size, linear, developed, direct, unshadowed })
}

impl Rendered {
    /// The shadow mask: pixels whose direct light is below half of what it is unshadowed
    /// (and that some direct light reaches unshadowed).
    pub fn shadow_mask(&self) -> Vec<bool> {
        self.direct.iter().zip(&self.unshadowed).map(|(&d, &u)| u > 1e-4 && d < 0.5 * u).collect()
    }
}

/// How one term compares.
#[derive(Debug, Clone, PartialEq)]
pub struct TermScore {
    /// The term.
    pub term: Term,
    /// ꟻLIP over the pixels where either image shows the term, the worse of its mean over the
    /// image and over the worst ninth of it (0: none differ; 1: most). For the shadows,
    /// 1 − the masks' intersection over union.
    pub error: f32,
    /// Mean absolute error of the developed values (0 to 1) over the same pixels.
    pub mean: f32,
    /// 95th percentile of the per-pixel largest channel error (0 to 1) over those pixels.
    pub p95: f32,
    /// Per pixel ꟻLIP (empty for the shadows).
    pub map: Vec<f32>,
    /// Whether either lesson has the term at all.
    pub present: bool,
    /// Points given, of `weight`.
    pub points: f32,
    /// The rubric's weight.
    pub weight: f32,
}

/// The whole grade.
#[derive(Debug, Clone)]
pub struct Grade {
    /// Each term's comparison, [`IMAGE_TERMS`] then the shadows.
    pub terms: Vec<TermScore>,
    /// What differs, the most points lost first.
    pub findings: Vec<findings::Finding>,
    /// Points given.
    pub points: f32,
    /// Points possible.
    pub total: f32,
    /// Whether `points` reach the rubric's pass mark.
    pub passed: bool,
}

/// Compares `student` with `reference` (the same size: the caller checks) under `rubric`.
pub fn grade(reference: &Rendered, student: &Rendered, rubric: &Rubric) -> Grade {
    let (w, h) = (reference.size.0 as usize, reference.size.1 as usize);
    let mut terms: Vec<TermScore> = IMAGE_TERMS
        .iter()
        .enumerate()
        .map(|(i, &term)| image_score(term, &reference.developed[i], &student.developed[i], (w, h), rubric))
        .collect();
    let (rm, sm) = (reference.shadow_mask(), student.shadow_mask());
    let union = rm.iter().zip(&sm).filter(|(a, b)| **a || **b).count();
    let both = rm.iter().zip(&sm).filter(|(a, b)| **a && **b).count();
    let error = if union == 0 { 0.0 } else { 1.0 - both as f32 / union as f32 };
    let rule = rubric.rule(Term::Shadows);
    terms.push(TermScore {
        term: Term::Shadows,
        error,
        mean: error,
        p95: error,
        map: Vec::new(),
        present: union > 0,
        points: rule.points(error),
        weight: rule.weight,
    });
    let found = findings::findings(reference, student, &terms);
    Grade::of(terms, found, rubric)
}

impl Grade {
    /// The grade of `terms` (their points summed) with `findings`.
    pub fn of(terms: Vec<TermScore>, findings: Vec<findings::Finding>, rubric: &Rubric) -> Grade {
        let points: f32 = terms.iter().map(|t| t.points).sum();
        let total: f32 = terms.iter().map(|t| t.weight).sum();
        Grade { terms, findings, points, total, passed: points + 1e-3 >= rubric.pass }
    }
}

/// The error of a ꟻLIP `map` over the `support` pixels: the worse of their mean over the
/// image and over the worst ninth of it (thirds by thirds), so a mistake confined to one
/// object is not averaged away by the rest of the picture.
fn pooled(map: &[f32], support: &[bool], w: usize) -> f32 {
    let h = map.len() / w.max(1);
    let mut cells = [(0.0f64, 0usize); 9];
    let mut whole = (0.0f64, 0usize);
    for (i, (&e, _)) in map.iter().zip(support).enumerate().filter(|(_, (_, s))| **s) {
        let (cx, cy) = ((i % w) * 3 / w, ((i / w) * 3 / h.max(1)).min(2));
        let c = &mut cells[cy * 3 + cx.min(2)];
        c.0 += f64::from(e);
        c.1 += 1;
        whole.0 += f64::from(e);
        whole.1 += 1;
    }
    let mean = |c: (f64, usize)| if c.1 == 0 { 0.0 } else { c.0 / c.1 as f64 };
    // A ninth needs a few pixels of the term to speak for it.
    let worst = cells.iter().filter(|c| c.1 * 9 >= whole.1.max(1) / 4).map(|&c| mean(c)).fold(0.0, f64::max);
    mean(whole).max(worst) as f32
}

/// Compares two developed 8-bit sRGB images (RGB, row-major, `size`) as `term`: ꟻLIP, mean
/// and 95th-percentile error over the pixels where either shows something (any channel at
/// least [`VISIBLE_CODE`]), and the rubric's points for it.
pub fn image_score(term: Term, reference: &[u8], student: &[u8], size: (usize, usize), rubric: &Rubric) -> TermScore {
    let to_f = |d: &[u8]| -> Vec<[f32; 3]> { d.chunks_exact(3).map(|p| [p[0], p[1], p[2]].map(|c| f32::from(c) / 255.0)).collect() };
    let (r, s) = (to_f(reference), to_f(student));
    let map = crate::cost::flip::flip_ldr(&r, &s, size.0, size.1, crate::cost::flip::DEFAULT_PPD);
    let shows = |p: &[f32; 3]| p.iter().any(|&c| c >= f32::from(VISIBLE_CODE) / 255.0 - 1e-6);
    let support: Vec<bool> = r.iter().zip(&s).map(|(a, b)| shows(a) || shows(b)).collect();
    let n = support.iter().filter(|&&b| b).count();
    let (error, mean, p95) = if n == 0 {
        (0.0, 0.0, 0.0)
    } else {
        let diffs: Vec<(f32, f32)> = r
            .iter()
            .zip(&s)
            .zip(&support)
            .filter(|(_, s)| **s)
            .map(|((a, b), _)| {
                let d = [0, 1, 2].map(|c| (a[c] - b[c]).abs());
                ((d[0] + d[1] + d[2]) / 3.0, d[0].max(d[1]).max(d[2]))
            })
            .collect();
        let mean = diffs.iter().map(|d| f64::from(d.0)).sum::<f64>() / n as f64;
        let worst: Vec<f32> = diffs.iter().map(|d| d.1).collect();
        (pooled(&map, &support, size.0), mean as f32, crate::cost::metrics::quantile(&worst, 0.95))
    };
    let rule = rubric.rule(term);
    TermScore { term, error, mean, p95, map, present: n > 0, points: rule.points(error), weight: rule.weight }
}

#[cfg(test)]
mod tests;
