//! Quality ladders: one approximation stepped from cheap to exact, each rung an override set.

use crate::lesson::{KeyPath, LadderKind, Lesson, Override};
use crate::scene::Shape;
use crate::shading::microfacet::Fresnel;

/// One rung: its label, the overrides that make it, and whether it is the exact ray cast.
#[derive(Debug, Clone, PartialEq)]
pub struct Rung {
    /// Label (`flat`, `segments 32`, `aa 4`, `schlick`).
    pub name: String,
    /// Overrides on top of the lesson's.
    pub sets: Vec<Override>,
    /// True for the analytic ray-cast rung (interpolation ladder only).
    pub exact: bool,
}

fn set(key: &str, value: toml::Value) -> Override {
    Override { arg: format!("{key}={value}"), path: KeyPath::parse(key).expect("ladder keys are valid paths"), value }
}

/// The rungs of `kind` for `lesson`, or why the ladder does not apply to it.
///
/// # Errors
/// A sentence naming what the lesson lacks (no sphere to tessellate, no physically based
/// material for the Fresnel ladder).
pub fn rungs(kind: LadderKind, lesson: &Lesson) -> Result<Vec<Rung>, String> {
    let rung = |name: String, sets: Vec<Override>| Rung { name, sets, exact: false };
    match kind {
        LadderKind::Interpolation => {
            let mut r: Vec<Rung> =
                ["flat", "gouraud", "phong"].iter().map(|i| rung((*i).into(), vec![set("render.interpolation", (*i).into())])).collect();
            r.push(Rung { name: "exact".into(), sets: Vec::new(), exact: true });
            Ok(r)
        }
        LadderKind::Tessellation => match lesson.objects.first().map(|o| &o.shape) {
            Some(Shape::UvSphere { .. }) => Ok([8i64, 16, 32, 64, 128, 256]
                .iter()
                .map(|s| rung(format!("{s}×{}", s / 2), vec![set("object.0.segments", (*s).into()), set("object.0.rings", (s / 2).into())]))
                .collect()),
            Some(Shape::Icosphere { .. }) => {
                Ok((0i64..=6).map(|s| rung(format!("subdivisions {s}"), vec![set("object.0.subdivisions", s.into())])).collect())
            }
            Some(Shape::Torus { .. }) => Ok([12i64, 24, 48, 96, 192]
                .iter()
                .map(|s| rung(format!("{s}×{}", s / 2), vec![set("object.0.segments", (*s).into()), set("object.0.sides", (s / 2).into())]))
                .collect()),
            _ => Err("the tessellation ladder needs a uv_sphere, icosphere or torus as the first object".into()),
        },
        LadderKind::Aa => Ok([1i64, 2, 4, 8].iter().map(|a| rung(format!("aa {a}"), vec![set("render.aa", (*a).into())])).collect()),
        LadderKind::Fresnel => {
            let names: Vec<&str> = lesson
                .materials
                .iter()
                .filter(|m| match m.brdf() {
                    // Conductors have their own exact Fresnel; the ladder compares dielectric ones.
                    Some(crate::shading::brdf::Brdf::CookTorrance(c)) => !matches!(c.fresnel, Fresnel::Conductor { .. } | Fresnel::None),
                    _ => false,
                })
                .map(|m| m.name.as_str())
                .collect();
            if names.is_empty() {
                return Err("the fresnel ladder needs a cook_torrance material with a dielectric (schlick or dielectric) Fresnel".into());
            }
            let all = |f: &str| names.iter().map(|n| set(&format!("material.{n}.fresnel"), f.into())).collect();
            Ok(vec![rung("schlick".into(), all("schlick")), rung("exact".into(), all("dielectric"))])
        }
    }
}
