//! `[[probe]]`: a finite position inside a box with B_min < B_max on every axis, the face
//! size within its limits, and at most [`MAX_PROBES`] probes.

use super::{R, Validator, keep};
use crate::lesson::error::LessonError;
use crate::lesson::limits::{MAX_PROBE_SIZE, MAX_PROBES, MIN_PROBE_SIZE};
use crate::lesson::path::KeyPath;
use crate::lesson::probe::{DEFAULT_PROBE_SIZE, ProbeSpec};
use crate::lesson::raw::RawProbe;
use crate::lesson::spans::Target;

/// Largest coordinate of a probe's position or box (as for lights and objects).
const MAX_COORD: f64 = 1e6;

impl Validator<'_> {
    /// Every `[[probe]]`, each error kept in `errors`.
    pub(super) fn probes(&self, root: &KeyPath, raw: &[RawProbe], errors: &mut Vec<LessonError>) -> Vec<ProbeSpec> {
        if raw.len() > MAX_PROBES {
            errors.push(self.err(
                &root.key("probe").index(MAX_PROBES),
                Target::Key,
                format!("{} probes: at most {MAX_PROBES} are allowed", raw.len()),
                Some("each probe renders the scene six times before the frame; one probe per room is typical".into()),
            ));
            return Vec::new();
        }
        raw.iter().enumerate().filter_map(|(i, p)| keep(errors, self.probe(&root.key("probe").index(i), p))).collect()
    }

    fn probe(&self, p: &KeyPath, raw: &RawProbe) -> R<ProbeSpec> {
        let position = self.vec3(&p.key("position"), raw.position, -MAX_COORD, MAX_COORD)?;
        let box_min = self.vec3(&p.key("box_min"), raw.box_min, -MAX_COORD, MAX_COORD)?;
        let box_max = self.vec3(&p.key("box_max"), raw.box_max, -MAX_COORD, MAX_COORD)?;
        let size = raw.size.map_or(Ok(DEFAULT_PROBE_SIZE), |v| self.integer(&p.key("size"), v, MIN_PROBE_SIZE, MAX_PROBE_SIZE))?;
        for (axis, name) in ["x", "y", "z"].iter().enumerate() {
            if box_min[axis] >= box_max[axis] {
                return Err(self.err(
                    &p.key("box_max"),
                    Target::Value,
                    format!("box_max.{name} ({}) must be greater than box_min.{name} ({})", box_max[axis], box_min[axis]),
                    Some("the box is the room the probe sees: box_min its smallest corner, box_max its largest, e.g. [-2, 0, -2] and [2, 3, 2]".into()),
                ));
            }
        }
        // Strictly inside: on a wall, R' = P − C vanishes for the directions into that wall.
        if !(position.cmpgt(box_min).all() && position.cmplt(box_max).all()) {
            return Err(self.err(
                &p.key("position"),
                Target::Value,
                format!(
                    "the probe's position [{}, {}, {}] is not inside its box [{}, {}, {}]..[{}, {}, {}]",
                    position.x, position.y, position.z, box_min.x, box_min.y, box_min.z, box_max.x, box_max.y, box_max.z
                ),
                Some(
                    "box projection measures from the position to the box's walls: put the position strictly inside box_min..box_max"
                        .into(),
                ),
            ));
        }
        let moved_to = match raw.moved_to {
            None => position,
            Some(v) => {
                let m = self.vec3(&p.key("moved_to"), v, -MAX_COORD, MAX_COORD)?;
                // The moved centre's own rays must leave the box by a wall, as the capture's do.
                if !(m.cmpgt(box_min).all() && m.cmplt(box_max).all()) {
                    return Err(self.err(
                        &p.key("moved_to"),
                        Target::Value,
                        format!("the probe's moved_to [{}, {}, {}] is not inside its box", m.x, m.y, m.z),
                        Some("moved_to is the moved centre C′ the capture is read from: put it strictly inside box_min..box_max, e.g. at the mirror object's centre".into()),
                    ));
                }
                m
            }
        };
        Ok(ProbeSpec { position, size, box_min, box_max, moved_to })
    }
}
