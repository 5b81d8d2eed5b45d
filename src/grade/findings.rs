//! What differs, in words a student understands: a missing or extra term, a term too bright
//! or too dark, a highlight too large or too small (the exponent), the light in the wrong
//! place, an unclamped N·L, shadows missing, extra or misplaced, a difference only in the
//! shadowed region, and otherwise the part of the image that differs most.

use super::rubric::Term;
use super::{IMAGE_TERMS, Rendered, TermScore, luminance};

/// One thing that differs.
#[derive(Debug, Clone, PartialEq)]
pub struct Finding {
    /// The term it is about.
    pub term: Term,
    /// Points that term lost.
    pub lost: f32,
    /// The sentence.
    pub text: String,
}

/// A term shows when its brightest pixel's luminance is above this (linear).
const SHOWS: f32 = 0.01;

/// Where `to` lies from `from` (points in [0, 1]², y down): "to the left", "up and to the right", ...
fn direction(from: (f32, f32), to: (f32, f32)) -> &'static str {
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let (h, v) = (dx.abs() > 0.5 * dy.abs(), dy.abs() > 0.5 * dx.abs());
    match (h, v, dx < 0.0, dy < 0.0) {
        (true, true, true, true) => "up and to the left",
        (true, true, false, true) => "up and to the right",
        (true, true, true, false) => "down and to the left",
        (true, true, false, false) => "down and to the right",
        (true, false, true, _) => "to the left",
        (true, false, false, _) => "to the right",
        (_, _, _, true) => "above",
        _ => "below",
    }
}

/// "its brightest part lies to the left of the reference's (at the bottom of the image)",
/// when the bright parts of `rl` and `sl` are more than 8% of the image apart.
fn moved(rl: &[f32], sl: &[f32], w: usize) -> Option<String> {
    let (rc, sc) = (bright_centroid(rl, w)?, bright_centroid(sl, w)?);
    (((rc.0 - sc.0).powi(2) + (rc.1 - sc.1).powi(2)).sqrt() > 0.08)
        .then(|| format!("its brightest part lies {} of the reference's (at the {} of the image)", direction(rc, sc), region(sc.0, sc.1)))
}

/// The part of the image around (x, y) in [0, 1]², in thirds: "upper left", "centre", ...
pub fn region(x: f32, y: f32) -> &'static str {
    const NAMES: [[&str; 3]; 3] =
        [["upper left", "top", "upper right"], ["left", "centre", "right"], ["lower left", "bottom", "lower right"]];
    let third = |t: f32| ((t * 3.0).floor().max(0.0) as usize).min(2);
    NAMES[third(y)][third(x)]
}

/// The region of `map` (per pixel, `w` wide) with the largest mean.
pub fn worst_region(map: &[f32], w: usize) -> &'static str {
    let h = map.len() / w.max(1);
    let mut sums = [[0.0f64; 3]; 3];
    let mut counts = [[0usize; 3]; 3];
    for (i, &e) in map.iter().enumerate() {
        let (x, y) = (i % w, i / w);
        let (cx, cy) = ((x * 3 / w).min(2), (y * 3 / h.max(1)).min(2));
        sums[cy][cx] += f64::from(e);
        counts[cy][cx] += 1;
    }
    let mut best = (0, 0, -1.0);
    for (cy, row) in sums.iter().enumerate() {
        for (cx, s) in row.iter().enumerate() {
            let mean = s / counts[cy][cx].max(1) as f64;
            if mean > best.2 {
                best = (cx, cy, mean);
            }
        }
    }
    region((best.0 as f32 + 0.5) / 3.0, (best.1 as f32 + 0.5) / 3.0)
}

/// The centroid of `lum` weighted by its square (the bright part), in [0, 1]²; `None` when dark.
fn bright_centroid(lum: &[f32], w: usize) -> Option<(f32, f32)> {
    let h = lum.len() / w.max(1);
    let (mut sx, mut sy, mut sw) = (0.0f64, 0.0f64, 0.0f64);
    for (i, &l) in lum.iter().enumerate() {
        let wt = f64::from(l.max(0.0)).powi(2);
        sx += wt * ((i % w) as f64 + 0.5);
        sy += wt * ((i / w) as f64 + 0.5);
        sw += wt;
    }
    (sw > 1e-12).then(|| ((sx / sw / w as f64) as f32, (sy / sw / h.max(1) as f64) as f32))
}

/// What the student may have set wrong when a term is missing.
fn missing_hint(t: Term) -> &'static str {
    match t {
        Term::Ambient => "is the material's `ambient` (K_amb), or the scene's, 0?",
        Term::Diffuse => "is `diffuse` (K_diff) 0, or does no light reach?",
        Term::Specular => "is `specular` (K_spec) 0, or the model `lambert`?",
        Term::Emission => "the reference's material has an `emission`",
        Term::Reflection => "the reference has a mirror or an environment",
        Term::Transmission => "the reference has glass",
        Term::Total | Term::Shadows | Term::Figure => "is anything drawn?",
    }
}

/// What differs when a term is too bright or too dark.
fn brightness_hint(t: Term) -> &'static str {
    match t {
        Term::Ambient => "`ambient` (K_amb) or the ambient light differs",
        Term::Diffuse => "`diffuse` (K_diff) or a light's `intensity` differs",
        Term::Specular => "`specular` (K_spec) or a light's `intensity` differs",
        Term::Emission => "`emission` differs",
        Term::Reflection => "a mirror's `tint` or the environment differs",
        Term::Transmission => "a glass's `tint` or `ior` differs",
        Term::Total | Term::Shadows | Term::Figure => "the exposure, the lights or the materials differ",
    }
}

/// Everything that differs between `student` and `reference`, the most points lost first.
pub fn findings(reference: &Rendered, student: &Rendered, scores: &[TermScore]) -> Vec<Finding> {
    let w = reference.size.0 as usize;
    let n = (reference.direct.len()).max(1) as f32;
    let mut out: Vec<Finding> = Vec::new();
    let (rm, sm) = (reference.shadow_mask(), student.shadow_mask());
    for (i, &term) in IMAGE_TERMS.iter().enumerate() {
        let score = &scores[i];
        let lost = score.weight - score.points;
        let rl: Vec<f32> = reference.linear[i].iter().map(|&c| luminance(c)).collect();
        let sl: Vec<f32> = student.linear[i].iter().map(|&c| luminance(c)).collect();
        let mean = |l: &[f32]| l.iter().map(|v| v.max(0.0)).sum::<f32>() / n;
        let peak = |l: &[f32]| l.iter().copied().fold(0.0f32, f32::max);
        let (r_mean, s_mean, r_peak, s_peak) = (mean(&rl), mean(&sl), peak(&rl), peak(&sl));
        let mut found: Vec<String> = Vec::new();
        let mut say = |text: String| found.push(text);
        let name = term.name();
        let mut lost = lost;
        if term == Term::Diffuse {
            let negative = |l: &[f32]| l.iter().filter(|&&v| v < -1e-4).count() as f32 / n;
            let (rn, sn) = (negative(&rl), negative(&sl));
            if sn > 0.002 && rn == 0.0 {
                say(format!(
                    "the diffuse term is negative on {:.0}% of the image (the side turned away from a light), which darkens the total below the ambient alone: N·L is not clamped; the term is K_diff max(N·L, 0) (`clamp_n_dot_l`)",
                    sn * 100.0
                ));
                // A negative term develops to black like a zero one: the total shows the loss.
                lost = lost.max(scores[0].weight - scores[0].points);
            }
        }
        if r_peak > SHOWS && s_peak <= 0.05 * r_peak {
            say(format!("the {name} term is missing: the reference's averages {r_mean:.3}, yours {s_mean:.3} ({})", missing_hint(term)));
        } else if s_peak > SHOWS && r_peak <= 0.05 * s_peak {
            say(format!("your lesson has a {name} term the reference has not (it averages {s_mean:.3})"));
        } else if r_peak > SHOWS && s_peak > SHOWS {
            let mut explained = false;
            if term == Term::Specular {
                let area = |l: &[f32], p: f32| l.iter().filter(|&&v| v > 0.5 * p).count().max(1) as f32;
                let ratio = area(&sl, s_peak) / area(&rl, r_peak);
                if ratio > 1.5 {
                    say(format!(
                        "the specular highlight covers {ratio:.1}× the reference's area: the exponent (`shininess`, K_shi) is too low"
                    ));
                    explained = true;
                } else if ratio < 1.0 / 1.5 {
                    say(format!(
                        "the specular highlight covers only {ratio:.2}× the reference's area: the exponent (`shininess`, K_shi) is too high"
                    ));
                    explained = true;
                } else if !(0.8..=1.25).contains(&(s_peak / r_peak)) {
                    say(format!("the specular highlight is {:.2}× as bright at its peak: {}", s_peak / r_peak, brightness_hint(term)));
                    explained = true;
                }
            }
            // Brighter or darker where the two differ (one object's colour, or everything).
            let differs: Vec<usize> = (0..score.map.len()).filter(|&p| score.map[p] > 0.05).collect();
            let sum = |l: &[f32]| differs.iter().map(|&p| f64::from(l[p].max(0.0))).sum::<f64>();
            let (rs, ss) = (sum(&rl), sum(&sl));
            let ratio = if rs > 1e-9 { (ss / rs) as f32 } else { 1.0 };
            let moved_to = if matches!(term, Term::Diffuse | Term::Specular) { moved(&rl, &sl, w) } else { None };
            if !explained && moved_to.is_none() && term != Term::Total && !differs.is_empty() && !(0.8..=1.25).contains(&ratio) {
                say(format!("the {name} term is {ratio:.2}× as bright as the reference's where they differ: {}", brightness_hint(term)));
            }
            if let Some(place) = moved_to {
                let what = if term == Term::Diffuse { "the diffuse term is lit from elsewhere" } else { "the specular highlight moved" };
                say(format!("{what}: {place}: a light is in the wrong place (check its `position` or `direction`)"));
            }
        }
        if lost > 0.0 && found.is_empty() && term != Term::Total {
            // Nothing specific: where it differs, and whether only in the shadows.
            let in_shadow: f64 =
                score.map.iter().zip(rm.iter().zip(&sm)).filter(|(_, (a, b))| **a || **b).map(|(e, _)| f64::from(*e)).sum();
            let all: f64 = score.map.iter().map(|&e| f64::from(e)).sum();
            let shadowed = rm.iter().zip(&sm).filter(|(a, b)| **a || **b).count() as f32 / n;
            let text = if all > 0.0 && in_shadow / all > 0.7 && shadowed < 0.5 {
                format!("the {name} term differs only in the shadowed region")
            } else {
                format!("the {name} term differs most at the {} of the image (ꟻLIP {:.2})", worst_region(&score.map, w), score.error)
            };
            found.push(text);
        }
        out.extend(found.into_iter().map(|text| Finding { term, lost, text }));
    }
    shadow_findings(&rm, &sm, &scores[IMAGE_TERMS.len()], n, &mut out);
    if out.is_empty()
        && let Some(total) = scores.first().filter(|s| s.weight - s.points > 0.0)
    {
        out.push(Finding {
            term: Term::Total,
            lost: total.weight - total.points,
            text: format!("the image differs most at the {} (ꟻLIP {:.2})", worst_region(&total.map, w), total.error),
        });
    }
    // The most points lost first; a term's own findings keep their order.
    out.sort_by(|a, b| b.lost.total_cmp(&a.lost));
    out
}

/// The shadows' findings: missing, extra, too large or small, misplaced.
fn shadow_findings(rm: &[bool], sm: &[bool], score: &TermScore, n: f32, out: &mut Vec<Finding>) {
    let lost = score.weight - score.points;
    let (ar, as_) = (rm.iter().filter(|&&b| b).count() as f32 / n, sm.iter().filter(|&&b| b).count() as f32 / n);
    let mut say = |text: String| out.push(Finding { term: Term::Shadows, lost, text });
    if ar > 0.005 && as_ < 0.1 * ar {
        say(format!(
            "the reference has shadows on {:.0}% of the image, yours none: is a light's or `[render]` `shadows` \"none\", or an object missing?",
            ar * 100.0
        ));
    } else if as_ > 0.005 && ar < 0.1 * as_ {
        say(format!("your shadows ({:.0}% of the image) are not in the reference", as_ * 100.0));
    } else if ar > 0.005 {
        let ratio = as_ / ar;
        if !(0.67..=1.5).contains(&ratio) {
            say(format!("your shadows cover {ratio:.1}× the reference's area"));
        } else if score.error > 0.4 {
            say(format!(
                "your shadows fall in a different place: they overlap the reference's by {:.0}% (check the lights' and the objects' positions)",
                (1.0 - score.error) * 100.0
            ));
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn regions_are_thirds_of_the_image() {
        assert_eq!(super::region(0.1, 0.1), "upper left");
        assert_eq!(super::region(0.5, 0.5), "centre");
        assert_eq!(super::region(0.99, 0.7), "lower right");
        assert_eq!(super::region(1.0, 0.0), "upper right");
    }
}
