//! The grading rubric: a weight and two error thresholds per term, and the pass mark. The
//! default is documented in docs/grading.md; a TOML file (`grade --rubric FILE`) changes any
//! part of it.

use crate::render::frame::Layer;
use serde::Deserialize;
use std::collections::BTreeMap;

/// What is graded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Term {
    /// The whole image.
    Total,
    /// L_glob⊗K_amb + Σ I_amb.
    Ambient,
    /// Σ d I_diff.
    Diffuse,
    /// Σ d I_spec.
    Specular,
    /// L_emi.
    Emission,
    /// What mirrors and the environment reflect.
    Reflection,
    /// What glass transmits.
    Transmission,
    /// Where the direct light is blocked.
    Shadows,
    /// A figure of the reference lesson (`grade --figure NAME`).
    Figure,
}

impl Term {
    /// Every term, in report order.
    pub const ALL: [Term; 9] = [
        Term::Total,
        Term::Ambient,
        Term::Diffuse,
        Term::Specular,
        Term::Emission,
        Term::Reflection,
        Term::Transmission,
        Term::Shadows,
        Term::Figure,
    ];

    /// The name in rubrics and reports.
    pub fn name(self) -> &'static str {
        match self {
            Term::Total => "total",
            Term::Ambient => "ambient",
            Term::Diffuse => "diffuse",
            Term::Specular => "specular",
            Term::Emission => "emission",
            Term::Reflection => "reflection",
            Term::Transmission => "transmission",
            Term::Shadows => "shadows",
            Term::Figure => "figure",
        }
    }

    /// The render layer it is read from (`None` for the shadows and a figure).
    pub fn layer(self) -> Option<Layer> {
        Some(match self {
            Term::Total => Layer::Total,
            Term::Ambient => Layer::Ambient,
            Term::Diffuse => Layer::Diffuse,
            Term::Specular => Layer::Specular,
            Term::Emission => Layer::Emission,
            Term::Reflection => Layer::Reflection,
            Term::Transmission => Layer::Transmission,
            Term::Shadows | Term::Figure => return None,
        })
    }
}

/// One term's rule: full points at or below `full` error, none at or above `zero`, linear between.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rule {
    /// Points the term is worth.
    pub weight: f32,
    /// Error (mean ꟻLIP; for the shadows 1 − IoU) at or below which all points are given.
    pub full: f32,
    /// Error at or above which none are.
    pub zero: f32,
}

impl Rule {
    /// The points for `error`.
    pub fn points(&self, error: f32) -> f32 {
        let t = ((error - self.full) / (self.zero - self.full).max(1e-6)).clamp(0.0, 1.0);
        // Rounded to tenths: a report shows 7.5, not 7.4999.
        (self.weight * (1.0 - t) * 10.0).round() / 10.0
    }
}

/// Weights and thresholds for every term, and the pass mark.
#[derive(Debug, Clone, PartialEq)]
pub struct Rubric {
    /// The rules, per term.
    pub rules: BTreeMap<Term, Rule>,
    /// Points needed to pass.
    pub pass: f32,
}

/// The default rule of `term`.
fn default_rule(term: Term) -> Rule {
    let (weight, full, zero) = match term {
        Term::Total => (25.0, 0.05, 0.4),
        Term::Ambient => (10.0, 0.05, 0.4),
        Term::Diffuse | Term::Specular => (20.0, 0.05, 0.4),
        Term::Emission | Term::Reflection | Term::Transmission => (5.0, 0.05, 0.4),
        Term::Shadows => (10.0, 0.1, 0.6),
        Term::Figure => (20.0, 0.05, 0.4),
    };
    Rule { weight, full, zero }
}

impl Default for Rubric {
    /// 25 points for the total, 20 each for diffuse and specular, 10 each for ambient and
    /// shadows, 5 each for emission, reflection and transmission (100), and 20 for a figure
    /// when one is graded; pass at 60.
    fn default() -> Rubric {
        Rubric { rules: Term::ALL.iter().map(|&t| (t, default_rule(t))).collect(), pass: 60.0 }
    }
}

/// A rubric file as written: any term may be left out (its default applies).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RubricFile {
    pass: Option<f32>,
    #[serde(default)]
    term: BTreeMap<String, PartialRule>,
}

/// A rule as written: any field may be left out.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PartialRule {
    weight: Option<f32>,
    full: Option<f32>,
    zero: Option<f32>,
}

impl Rubric {
    /// The rule of `term`.
    pub fn rule(&self, term: Term) -> Rule {
        self.rules.get(&term).copied().unwrap_or_else(|| default_rule(term))
    }

    /// Reads a rubric from TOML `text` (`file` names it in messages).
    ///
    /// # Errors
    /// A message naming the file, the line and column when TOML locates it, and the fix.
    pub fn parse(text: &str, file: &str) -> Result<Rubric, String> {
        let raw: RubricFile = toml::from_str(text).map_err(|e| {
            let at = e.span().map_or(String::new(), |s| {
                let (line, col) = crate::lesson::spans::line_col(text, s.start);
                format!(":{line}:{col}")
            });
            format!(
                "{file}{at}: {}\n  hint: a rubric has `pass = 60` and `[term.NAME]` tables with `weight`, `full` and `zero` (docs/grading.md)",
                e.message()
            )
        })?;
        let mut rubric = Rubric::default();
        for (name, r) in raw.term {
            let Some(term) = Term::ALL.into_iter().find(|t| t.name() == name) else {
                let names: Vec<&str> = Term::ALL.iter().map(|t| t.name()).collect();
                return Err(format!("{file}: `term.{name}`: unknown term\n  hint: terms are {}", names.join(", ")));
            };
            let d = rubric.rule(term);
            let rule = Rule { weight: r.weight.unwrap_or(d.weight), full: r.full.unwrap_or(d.full), zero: r.zero.unwrap_or(d.zero) };
            let ok = |v: f32, lo: f32, hi: f32| v.is_finite() && (lo..=hi).contains(&v);
            if !(ok(rule.weight, 0.0, 1000.0) && ok(rule.full, 0.0, 1.0) && ok(rule.zero, 0.0, 1.0) && rule.full < rule.zero) {
                return Err(format!(
                    "{file}: `term.{name}`: weight {}, full {}, zero {}: give a weight of 0 to 1000 and 0 ≤ full < zero ≤ 1\n  hint: e.g. `weight = 20`, `full = 0.05`, `zero = 0.4`",
                    rule.weight, rule.full, rule.zero
                ));
            }
            rubric.rules.insert(term, rule);
        }
        if let Some(p) = raw.pass {
            if !(p.is_finite() && p >= 0.0) {
                return Err(format!("{file}: `pass = {p}`: give the points needed to pass, 0 or more\n  hint: e.g. `pass = 60`"));
            }
            rubric.pass = p;
        }
        Ok(rubric)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_fall_linearly_between_the_thresholds() {
        let r = Rule { weight: 20.0, full: 0.1, zero: 0.5 };
        assert_eq!((r.points(0.0), r.points(0.1), r.points(0.3), r.points(0.5), r.points(0.9)), (20.0, 20.0, 10.0, 0.0, 0.0));
        let d = Rubric::default();
        let whole: f32 = Term::ALL.iter().filter(|&&t| t != Term::Figure).map(|&t| d.rule(t).weight).sum();
        assert_eq!(whole, 100.0, "the default rubric is out of 100 without a figure");
    }

    #[test]
    fn a_rubric_file_changes_what_it_names_and_bad_ones_say_where() {
        let r = Rubric::parse("pass = 50\n[term.specular]\nweight = 40\n", "r.toml").unwrap();
        assert_eq!((r.pass, r.rule(Term::Specular).weight, r.rule(Term::Specular).full), (50.0, 40.0, 0.05));
        assert_eq!(r.rule(Term::Diffuse), Rubric::default().rule(Term::Diffuse));
        let e = Rubric::parse("pass = 50\n[term.specular]\nweigth = 40\n", "r.toml").unwrap_err();
        assert!(e.starts_with("r.toml:3:1: ") && e.contains("weigth"), "{e}");
        let e = Rubric::parse("[term.glossy]\nweight = 4\n", "r.toml").unwrap_err();
        assert!(e.contains("unknown term") && e.contains("specular"), "{e}");
        let e = Rubric::parse("[term.diffuse]\nfull = 0.5\nzero = 0.2\n", "r.toml").unwrap_err();
        assert!(e.contains("full < zero"), "{e}");
    }
}
