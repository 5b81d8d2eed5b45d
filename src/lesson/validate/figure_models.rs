//! `walk`, `bsdf` and `bssrdf` figures: charts of a model alone (a slab's random walk, a rough
//! dielectric, a subsurface material's exit profile), with no scene rendered, so none of the
//! keys that vary a scene.

use super::{R, Validator};
use crate::lesson::figure::{DEFAULT_WALKS, FigureBody, FigureSpec, MAX_WALKS};
use crate::lesson::path::KeyPath;
use crate::lesson::raw::RawFigure;
use crate::lesson::spans::Target;
use crate::shading::brdf::Brdf;
use crate::shading::material::Material;

/// The keys of the other kinds, which a model's chart does not read.
const SCENE_KEYS: [&str; 20] = [
    "vary",
    "values",
    "rows",
    "cols",
    "labels",
    "layers",
    "layer",
    "cell",
    "materials",
    "lights",
    "azimuth_deg",
    "swap",
    "terms",
    "normals",
    "ladder",
    "repeat",
    "solvers",
    "tolerance",
    "pixels",
    "colorbar",
];

impl Validator<'_> {
    /// A `walk` figure: a random walk in a slab.
    pub(super) fn walk_figure(&self, p: &KeyPath, f: &RawFigure) -> R<FigureSpec> {
        self.refuse_figure_keys(p, f, &SCENE_KEYS, "by a `walk` figure (it walks light through a slab of `scattering_albedo`)")?;
        self.refuse_figure_keys(p, f, &["ior", "roughness"], "by a `walk` figure (only `bsdf` figures draw a rough dielectric)")?;
        let albedo = match &f.scattering_albedo {
            Some(c) => self.triple(&p.key("scattering_albedo"), c, 0.0, 1.0)?,
            None => {
                return Err(self.err(
                    p,
                    Target::Key,
                    "a `walk` figure needs `scattering_albedo`",
                    Some("add e.g. `scattering_albedo = [0.999, 0.98, 0.9]`: the share of each channel kept at every scattering".into()),
                ));
            }
        };
        let incidence =
            self.one_incidence(p, f, "walk", 0.0, "give e.g. `incidence = [60]`, or drop the key for a beam along the normal")?;
        let walks = match f.walks {
            Some(n) => self.integer(&p.key("walks"), n, 1000, MAX_WALKS as i64)?,
            None => DEFAULT_WALKS,
        };
        let thickness = match f.thickness {
            Some(t) => Some(self.number(&p.key("thickness"), t, 1e-3, 1e6)? as f64),
            None => None,
        };
        self.spec(p, f, None, FigureBody::Walk { albedo, incidence, walks, thickness }, false)
    }

    /// A `bsdf` figure: a rough dielectric beside the smooth glass.
    pub(super) fn bsdf_figure(&self, p: &KeyPath, f: &RawFigure) -> R<FigureSpec> {
        self.refuse_figure_keys(p, f, &SCENE_KEYS, "by a `bsdf` figure (it draws a rough dielectric of `ior` and `roughness`)")?;
        let ior = match f.ior {
            Some(v) => self.number(&p.key("ior"), v, 1.01, 4.0)? as f64,
            None => 1.5,
        };
        let list = f.roughness.clone().unwrap_or_else(|| vec![0.1, 0.3, 0.6]);
        if list.is_empty() || list.len() > 4 {
            return Err(self.err(
                &p.key("roughness"),
                Target::Value,
                "give 1 to 4 roughnesses",
                Some("e.g. `roughness = [0.1, 0.3, 0.6]` (α = roughness²; the smooth glass is drawn beside them)".into()),
            ));
        }
        let mut roughness = Vec::with_capacity(list.len());
        for (i, r) in list.iter().enumerate() {
            roughness.push(self.number(&p.key("roughness").index(i), *r, 0.02, 1.0)? as f64);
        }
        let incidence = self.one_incidence(p, f, "bsdf", 40.0, "give e.g. `incidence = [40]`: the energy chart covers every angle")?;
        self.spec(p, f, None, FigureBody::Bsdf { ior, roughness, incidence }, false)
    }

    /// A `bssrdf` figure: one principled material that walks under its surface.
    pub(super) fn bssrdf_figure(&self, p: &KeyPath, f: &RawFigure, defined: &[Material]) -> R<FigureSpec> {
        let why = "by a `bssrdf` figure (it walks light into a half-space of its one material)";
        let walk_keys = ["scattering_albedo", "walks", "thickness", "ior", "roughness", "incidence"];
        self.refuse_figure_keys(p, f, &SCENE_KEYS.into_iter().filter(|k| *k != "materials").collect::<Vec<_>>(), why)?;
        self.refuse_figure_keys(p, f, &walk_keys, why)?;
        let walking: Vec<&str> =
            defined.iter().filter(|m| matches!(m.brdf(), Some(Brdf::Principled(pr)) if pr.walks())).map(|m| m.name.as_str()).collect();
        let choose = if walking.is_empty() {
            "no material here walks: give a principled material `subsurface` > 0 and a `subsurface_radius`".to_string()
        } else {
            format!("materials that walk here: {}", walking.join(", "))
        };
        let name = match f.materials.as_deref() {
            Some([one]) => one,
            Some(_) => {
                let hint = format!("name exactly one, e.g. `materials = [\"skin\"]`; {choose}");
                return Err(self.err(&p.key("materials"), Target::Value, "a `bssrdf` figure takes one material", Some(hint)));
            }
            None => return Err(self.err(p, Target::Key, "a `bssrdf` figure needs `materials`", Some(choose))),
        };
        if !walking.contains(&name.as_str()) {
            let what = if defined.iter().any(|m| &m.name == name) { "does not walk under its surface" } else { "is not a material here" };
            return Err(self.err(&p.key("materials").index(0), Target::Value, format!("`{name}` {what}"), Some(choose)));
        }
        self.spec(p, f, None, FigureBody::Bssrdf { material: name.clone() }, false)
    }

    /// The one angle of incidence a `kind` figure takes (`default` without the key), in degrees.
    fn one_incidence(&self, p: &KeyPath, f: &RawFigure, kind: &str, default: f64, hint: &str) -> R<f64> {
        match f.incidence.as_deref() {
            None => Ok(default),
            Some([a]) => Ok(self.number(&p.key("incidence").index(0), *a, 0.0, 89.9)? as f64),
            Some(_) => Err(self.err(
                &p.key("incidence"),
                Target::Value,
                format!("a `{kind}` figure takes one angle of incidence"),
                Some(hint.into()),
            )),
        }
    }
}
