//! A quality ladder as data: its rungs, each an override set on top of the lesson, and the
//! reference it may name for itself. `ladder` and `radiosity` build them; `measure` runs them.

use crate::lesson::{KeyPath, Override};

/// One rung: its label, the overrides that make it, and whether it is the exact ray cast.
#[derive(Debug, Clone, PartialEq)]
pub struct Rung {
    /// Label (`flat`, `segments 32`, `aa 4`, `schlick`).
    pub name: String,
    /// Overrides on top of the lesson's.
    pub sets: Vec<Override>,
    /// True for the analytic ray-cast rung (interpolation ladder only).
    pub exact: bool,
    /// The series it belongs to when a ladder compares two ways of doing one thing (the
    /// chart joins a series' rungs); empty for a single series.
    pub series: String,
}

/// A reference a ladder names for itself: the lesson with these overrides, rendered by the
/// rasterizer.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedReference {
    /// A short name that reads after "against" (`ray-cast shadows`).
    pub name: String,
    /// Overrides on top of the lesson's.
    pub sets: Vec<Override>,
    /// Rect lights give their exact unoccluded irradiance by Lambert's polygon formula
    /// instead of samples ([`crate::lesson::RenderSettings::area_reference`]).
    pub exact_area: bool,
    /// One line for reports: what it is and why it is the reference.
    pub describe: String,
}

/// A ladder for one lesson: its rungs, cheap to costly, and its own reference if it names one.
#[derive(Debug, Clone, PartialEq)]
pub struct Ladder {
    /// The rungs.
    pub rungs: Vec<Rung>,
    /// `None`: the exact ray cast when the shapes allow it (not for `fresnel`), else the finest rung.
    pub reference: Option<NamedReference>,
}

/// The override `key=value`, as `--set` would parse it.
pub fn set(key: &str, value: toml::Value) -> Override {
    Override { arg: format!("{key}={value}"), path: KeyPath::parse(key).expect("ladder keys are valid paths"), value }
}
