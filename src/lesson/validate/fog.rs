//! `[fog]`: the kind, the keys it reads (others are errors), their ranges, `start` < `end`,
//! `g` strictly inside (−1, 1) and the step limit.

use super::{R, Validator};
use crate::lesson::fog::{Fog, FogDistance, FogKind, FogSampling, Medium};
use crate::lesson::limits::MAX_FOG_STEPS;
use crate::lesson::path::KeyPath;
use crate::lesson::raw::RawFog;
use crate::lesson::spans::Target;
use glam::Vec3;

/// Largest density or coefficient per unit length: 1000 makes a unit of distance opaque to
/// e^(−1000); anything larger is a typo.
const MAX_COEFFICIENT: f64 = 1000.0;
/// Largest fog distance (`start`, `end`).
const MAX_DISTANCE: f64 = 1e6;
/// Ray-march steps when `steps` is not given.
pub const DEFAULT_STEPS: u32 = 64;
/// C_fog when `color` is not given: a light grey.
const DEFAULT_COLOR: f32 = 0.6;

impl Validator<'_> {
    pub(super) fn fog(&self, p: &KeyPath, f: &RawFog) -> R<Fog> {
        let names = FogKind::KEYS.map(|(n, _)| (n, n));
        let kind = self.choice(&p.key("kind"), &f.kind, &names)?;
        let reads = FogKind::KEYS.iter().find(|(n, _)| *n == kind).map_or(&[][..], |(_, k)| *k);
        for (key, set) in [
            ("color", f.color.is_some()),
            ("start", f.start.is_some()),
            ("end", f.end.is_some()),
            ("density", f.density.is_some()),
            ("distance", f.distance.is_some()),
            ("sigma_s", f.sigma_s.is_some()),
            ("sigma_a", f.sigma_a.is_some()),
            ("g", f.g.is_some()),
            ("steps", f.steps.is_some()),
            ("sampling", f.sampling.is_some()),
        ] {
            if set && !reads.contains(&key) {
                return Err(self.err(
                    &p.key(key),
                    Target::Key,
                    format!("`{key}` is not used by `{kind}` fog"),
                    Some(format!("`{kind}` fog reads: kind, {}; remove `{key}`", reads.join(", "))),
                ));
            }
        }
        let need = |key: &str, v: Option<f64>| -> R<f64> {
            v.ok_or_else(|| {
                self.err(&p.key(key), Target::Key, format!("`{kind}` fog needs `{key}`"), Some(format!("add `{key} = ...` to [fog]")))
            })
        };
        let color = f.color.as_ref().map_or(Ok(Vec3::splat(DEFAULT_COLOR)), |c| self.color(&p.key("color"), c, 0.0, 1e6))?;
        let distance = match &f.distance {
            Some(s) => self.choice(&p.key("distance"), s, &FogDistance::NAMES)?,
            None => FogDistance::default(),
        };
        let kind = match kind {
            "linear" => {
                let start = f.start.map_or(Ok(0.0), |v| self.number(&p.key("start"), v, 0.0, MAX_DISTANCE))?;
                let end = self.number(&p.key("end"), need("end", f.end)?, 0.0, MAX_DISTANCE)?;
                if start >= end {
                    return Err(self.err(
                        &p.key("end"),
                        Target::Value,
                        format!("`end` ({end}) must be greater than `start` ({start})"),
                        Some("linear fog runs from `start` (no fog) to `end` (all fog), e.g. start = 2, end = 10".into()),
                    ));
                }
                FogKind::Linear { start, end }
            }
            "exp" | "exp2" => {
                let density = self.number(&p.key("density"), need("density", f.density)?, 0.0, MAX_COEFFICIENT)?;
                if kind == "exp" { FogKind::Exp { density } } else { FogKind::Exp2 { density } }
            }
            _ => {
                let sigma_s = match f.sigma_s {
                    Some(v) => self.number(&p.key("sigma_s"), v, 0.0, MAX_COEFFICIENT)?,
                    None => {
                        return Err(self.err(
                            &p.key("sigma_s"),
                            Target::Key,
                            "`medium` fog needs `sigma_s`",
                            Some("add `sigma_s = 0.1` (scattering per unit length) to [fog]".into()),
                        ));
                    }
                };
                let sigma_a = f.sigma_a.map_or(Ok(0.0), |v| self.number(&p.key("sigma_a"), v, 0.0, MAX_COEFFICIENT))?;
                let g = match f.g {
                    Some(g) if g.is_finite() && (g <= -1.0 || g >= 1.0) => {
                        return Err(self.err(
                            &p.key("g"),
                            Target::Value,
                            format!("g = {g} is outside (−1, 1): the Henyey-Greenstein phase function is not defined there"),
                            Some("g is the mean cosine of scattering: 0 isotropic, 0.8 strongly forward, −0.5 backward; |g| < 1".into()),
                        ));
                    }
                    Some(g) => self.number(&p.key("g"), g, -1.0, 1.0)?,
                    None => 0.0,
                };
                let steps = f.steps.map_or(Ok(DEFAULT_STEPS), |v| self.integer(&p.key("steps"), v, 1, MAX_FOG_STEPS))?;
                let sampling =
                    f.sampling.as_ref().map_or(Ok(FogSampling::default()), |s| self.choice(&p.key("sampling"), s, &FogSampling::NAMES))?;
                FogKind::Medium(Medium { sigma_s, sigma_a, g, steps, sampling })
            }
        };
        Ok(Fog { kind, color, distance })
    }
}
