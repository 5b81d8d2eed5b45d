//! The keys every `[[figure]]` kind shares: `cell`, `fit`, `colorbar`, and the validated
//! spec they make with the kind's body.

use super::{R, Validator};
use crate::lesson::figure::{FigureBody, FigureSpec};
use crate::lesson::limits::FIT_SIDE;
use crate::lesson::path::KeyPath;
use crate::lesson::raw::RawFigure;
use crate::lesson::spans::Target;

impl Validator<'_> {
    /// The validated figure: the keys every kind shares, with its `cell`, `body` and `diff`.
    pub(super) fn spec(&self, p: &KeyPath, f: &RawFigure, cell: Option<(u32, u32)>, body: FigureBody, diff: bool) -> R<FigureSpec> {
        let colorbar = self.colorbar(p, f, &body, diff)?;
        Ok(FigureSpec {
            name: f.name.clone(),
            title: self.opt_text(&p.key("title"), f.title.as_ref())?,
            caption: self.opt_text(&p.key("caption"), f.caption.as_ref())?,
            cell,
            body,
            diff,
            fit: self.fit(p, f)?,
            colorbar,
        })
    }

    /// `colorbar = { label, radiance_per_unit }`: only under cells that show one layer, and
    /// not with `diff` (its difference row has its own bar).
    fn colorbar(&self, p: &KeyPath, f: &RawFigure, body: &FigureBody, diff: bool) -> R<Option<crate::lesson::figure::ValueBar>> {
        let Some(bar) = &f.colorbar else { return Ok(None) };
        if !matches!(body, FigureBody::Compare { .. } | FigureBody::Sweep { .. } | FigureBody::Grid { .. }) {
            return self
                .unused(p, "colorbar", &Some(()), "by this figure (only `compare`, `sweep` and `grid` cells show a quantity)")
                .map(|()| None);
        }
        if diff {
            return self.unused(p, "colorbar", &Some(()), "with `diff = true` (the difference row has its own colour bar)").map(|()| None);
        }
        let cp = p.key("colorbar");
        let label = self.text(&cp.key("label"), &bar.label)?;
        if label.trim().is_empty() {
            return Err(self.err(
                &cp.key("label"),
                Target::Value,
                "the colour bar needs a label",
                Some("say what the greys measure, with its unit, e.g. `label = \"irradiance E (W/m²)\"`".into()),
            ));
        }
        let radiance_per_unit = self.number(&cp.key("radiance_per_unit"), bar.radiance_per_unit, 1e-6, 1e6)?;
        Ok(Some(crate::lesson::figure::ValueBar { label, radiance_per_unit }))
    }

    /// `cell = [w, h]`, each 8 to 4096 pixels.
    pub(super) fn cell_size(&self, p: &KeyPath, f: &RawFigure) -> R<Option<(u32, u32)>> {
        let Some([w, h]) = f.cell else { return Ok(None) };
        let cp = p.key("cell");
        Ok(Some((self.integer(&cp, w, 8, 4096)?, self.integer(&cp, h, 8, 4096)?)))
    }

    /// `fit = "1920x1080"` or `[1920, 1080]`: the slide the figure is laid out for.
    fn fit(&self, p: &KeyPath, f: &RawFigure) -> R<Option<(u32, u32)>> {
        let Some(v) = &f.fit else { return Ok(None) };
        let bad = || {
            self.err(
                &p.key("fit"),
                Target::Value,
                "`fit` is a slide size",
                Some(format!("e.g. `fit = \"1920x1080\"` or `fit = [1920, 1080]`, each side {} to {}", FIT_SIDE.0, FIT_SIDE.1)),
            )
        };
        let (w, h) = match v {
            toml::Value::String(s) => crate::lesson::figure::parse_slide_size(s).ok_or_else(bad)?,
            toml::Value::Array(a) => match a.as_slice() {
                [toml::Value::Integer(w), toml::Value::Integer(h)] => (*w, *h),
                _ => return Err(bad()),
            },
            _ => return Err(bad()),
        };
        let fp = p.key("fit");
        Ok(Some((self.integer(&fp, w, FIT_SIDE.0, FIT_SIDE.1)?, self.integer(&fp, h, FIT_SIDE.0, FIT_SIDE.1)?)))
    }
}
