//! Bad `[fog]` values: negative coefficients, g outside (−1, 1), start ≥ end, too many steps,
//! keys the kind does not read, non-finite numbers; each exits 2 before any work.

use super::{Workspace, append, fails};

/// `[fog]` appended to the base lesson: its header on line 18, `kind` on 19, the next key on 20.
fn fog(keys: &str) -> String {
    append(&format!("\n[fog]\n{keys}"))
}

#[test]
fn negative_coefficients() {
    fails(&fog("kind = \"medium\"\nsigma_s = -0.1\n"))
        .at(20, 11)
        .key("fog.sigma_s")
        .says("-0.1 is out of range: allowed 0 to 1000")
        .hint("scattering and absorption per unit length");
    fails(&fog("kind = \"medium\"\nsigma_s = 0.1\nsigma_a = -2\n")).at(21, 11).key("fog.sigma_a").says("-2 is out of range");
    fails(&fog("kind = \"exp\"\ndensity = -0.5\n")).at(20, 11).key("fog.density").says("-0.5 is out of range");
}

#[test]
fn g_must_lie_strictly_inside_minus_one_to_one() {
    for g in ["1", "1.0", "-1", "-3.5"] {
        fails(&fog(&format!("kind = \"medium\"\nsigma_s = 0.1\ng = {g}\n")))
            .at(21, 5)
            .key("fog.g")
            .says("is outside (−1, 1)")
            .hint("|g| < 1");
    }
    fails(&fog("kind = \"medium\"\nsigma_s = 0.1\ng = nan\n")).at(21, 5).key("fog.g").says("must be a finite number");
}

#[test]
fn linear_start_must_be_below_end() {
    for (start, end) in [("5", "5"), ("8", "2")] {
        fails(&fog(&format!("kind = \"linear\"\nstart = {start}\nend = {end}\n")))
            .at(21, 7)
            .key("fog.end")
            .says("must be greater than `start`")
            .hint("start = 2, end = 10");
    }
    fails(&fog("kind = \"linear\"\nstart = 1\n")).at(18, 1).key("fog.end").says("`linear` fog needs `end`");
}

#[test]
fn steps_over_the_limit_are_refused_in_the_file_and_on_the_command_line() {
    fails(&fog("kind = \"medium\"\nsigma_s = 0.1\nsteps = 4097\n"))
        .at(21, 9)
        .key("fog.steps")
        .says("4097 is out of range: allowed 1 to 4096")
        .hint("the limit");
    fails(&fog("kind = \"medium\"\nsigma_s = 0.1\nsteps = 0\n")).key("fog.steps").says("allowed 1 to 4096");
    let ws = Workspace::new(&fog("kind = \"medium\"\nsigma_s = 0.1\n"));
    ws.render_fails(&["--set", "fog.steps=100000"]).says("--set fog.steps=100000").says("allowed 1 to 4096");
}

#[test]
fn keys_the_kind_does_not_read_and_unknown_kinds() {
    fails(&fog("kind = \"medium\"\nsigma_s = 0.1\ndensity = 0.2\n"))
        .at(21, 1)
        .key("fog.density")
        .says("`density` is not used by `medium` fog")
        .hint("sigma_s, sigma_a, g, steps");
    fails(&fog("kind = \"exp\"\ndensity = 0.2\nsteps = 8\n")).key("fog.steps").says("not used by `exp` fog");
    fails(&fog("kind = \"exp3\"\ndensity = 0.2\n"))
        .at(19, 8)
        .key("fog.kind")
        .says("unknown value `exp3`")
        .hint("Allowed: linear, exp, exp2, medium");
    fails(&fog("kind = \"medium\"\nsigma = 0.2\n")).at(20, 1).key("fog.sigma").says("unknown key `sigma`");
    fails(&fog("kind = \"medium\"\n")).key("fog.sigma_s").says("`medium` fog needs `sigma_s`");
}
