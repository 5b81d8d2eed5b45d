//! Bad `[[probe]]` tables: a box that does not hold its position, `box_min` not below
//! `box_max`, a `moved_to` outside the box, non-finite numbers, a size out of range, an unknown `reflections`; each exits
//! 2 before any work and writes nothing.

use super::{Workspace, append, fails};

/// A `[[probe]]` appended to the base lesson: its header on line 18, then `position` (19),
/// `box_min` (20), `box_max` (21) and `extra` (22).
fn probe(position: &str, box_min: &str, box_max: &str, extra: &str) -> String {
    append(&format!("\n[[probe]]\nposition = {position}\nbox_min = {box_min}\nbox_max = {box_max}\n{extra}"))
}

#[test]
fn a_box_that_does_not_hold_its_position() {
    fails(&probe("[0, 5, 0]", "[-2, 0, -2]", "[2, 3, 2]", ""))
        .at(19, 12)
        .key("probe.0.position")
        .says("is not inside its box")
        .hint("strictly inside box_min..box_max");
    // On a wall is not inside: R' = P − C would vanish there.
    fails(&probe("[2, 1, 0]", "[-2, 0, -2]", "[2, 3, 2]", "")).key("probe.0.position").says("is not inside its box");
}

#[test]
fn a_moved_centre_outside_the_box() {
    fails(&probe("[0, 1, 0]", "[-2, 0, -2]", "[2, 3, 2]", "moved_to = [0, 1, 3]\n"))
        .at(22, 12)
        .key("probe.0.moved_to")
        .says("the probe's moved_to [0, 1, 3] is not inside its box")
        .hint("the moved centre C′");
    fails(&probe("[0, 1, 0]", "[-2, 0, -2]", "[2, 3, 2]", "moved_to = [0, inf, 0]\n"))
        .key("probe.0.moved_to")
        .says("must be a finite number");
}

#[test]
fn box_min_must_lie_below_box_max_on_every_axis() {
    fails(&probe("[0, 1, 0]", "[-2, 0, -2]", "[2, 3, -2]", ""))
        .at(21, 11)
        .key("probe.0.box_max")
        .says("box_max.z (-2) must be greater than box_min.z (-2)")
        .hint("smallest corner");
    fails(&probe("[0, 1, 0]", "[2, 0, -2]", "[-2, 3, 2]", "")).key("probe.0.box_max").says("box_max.x (-2) must be greater");
}

#[test]
fn non_finite_numbers_and_sizes_out_of_range() {
    fails(&probe("[0, nan, 0]", "[-2, 0, -2]", "[2, 3, 2]", "")).key("probe.0.position").says("must be a finite number");
    fails(&probe("[0, 1, 0]", "[-inf, 0, -2]", "[2, 3, 2]", "")).key("probe.0.box_min").says("must be a finite number");
    fails(&probe("[0, 1, 0]", "[-2, 0, -2]", "[2, 3, 2]", "size = 4096\n"))
        .at(22, 8)
        .key("probe.0.size")
        .says("4096 is out of range: allowed 8 to 1024");
    fails(&probe("[0, 1, 0]", "[-2, 0, -2]", "[2, 3, 2]", "size = 0\n")).key("probe.0.size").says("allowed 8 to 1024");
    let ws = Workspace::new(&probe("[0, 1, 0]", "[-2, 0, -2]", "[2, 3, 2]", ""));
    ws.render_fails(&["--set", "probe.0.size=100000"]).says("--set probe.0.size=100000").says("allowed 8 to 1024");
}

#[test]
fn missing_keys_and_unknown_reflections() {
    fails(&append("\n[[probe]]\nposition = [0, 1, 0]\nbox_min = [-2, 0, -2]\n")).says("box_max");
    fails(&append("\n[render]\nreflections = \"probes\"\n"))
        .at(19, 15)
        .key("render.reflections")
        .says("unknown value `probes`")
        .hint("did you mean `probe`?");
}
