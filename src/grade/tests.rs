//! The grader on planted mistakes: each must be named, the reference itself must get every point.

use super::*;
use crate::lesson::settings::Tonemap;

/// A red plastic sphere over a grey floor, a point light above and to the right: every term
/// the classic equation has, and a shadow.
const REFERENCE: &str = r#"
[camera]
position = [0.0, 3.0, 5.0]
look_at = [0.0, 0.4, 0.0]
fov_deg = 40.0
size = [96, 96]

[[object]]
shape = "plane"
scale = 3
material = "floor"

[[object]]
shape = "uv_sphere"
segments = 32
rings = 16
translate = [0.0, 1.0, 0.0]
material = "plastic"

[material.floor]
model = "lambert"
diffuse = 0.6
ambient = 0.6

[material.plastic]
model = "phong"
diffuse = [0.7, 0.1, 0.1]
ambient = [0.7, 0.1, 0.1]
specular = 0.6
shininess = 64

[[light]]
kind = "point"
position = [2.5, 4.0, 2.0]
intensity = 1.0

[scene]
ambient = 0.15

[render]
interpolation = "phong"
"#;

const DEVELOP: Develop = Develop { exposure: 0.0, tonemap: Tonemap::Clamp };

fn rendered(text: &str) -> Rendered {
    let lesson = crate::lesson::parse(text, std::path::Path::new("grade-test.toml"), &[]).expect("a valid lesson");
    render(&lesson, DEVELOP).expect("renders")
}

/// The grade of `text` against the reference, and its findings as one text.
fn graded(text: &str) -> (Grade, String) {
    let g = grade(&rendered(REFERENCE), &rendered(text), &rubric::Rubric::default());
    let words = g.findings.iter().map(|f| format!("[{} −{}] {}", f.term.name(), f.lost, f.text)).collect::<Vec<_>>().join("\n");
    (g, words)
}

fn score(g: &Grade, term: Term) -> &TermScore {
    g.terms.iter().find(|t| t.term == term).expect("every term is scored")
}

#[test]
fn the_reference_against_itself_gets_every_point_and_no_finding() {
    let (g, words) = graded(REFERENCE);
    assert_eq!((g.points, g.total, g.passed), (100.0, 100.0, true), "{words}");
    assert!(g.findings.is_empty(), "{words}");
    assert!(g.terms.iter().all(|t| t.error == 0.0 && t.p95 == 0.0), "{:?}", g.terms.iter().map(|t| t.error).collect::<Vec<_>>());
    // The shadow is there to compare: the sphere's on the floor.
    let r = rendered(REFERENCE);
    let shadowed = r.shadow_mask().iter().filter(|&&b| b).count();
    assert!(shadowed > 96 * 96 / 100, "the reference has a shadow ({shadowed} px)");
}

#[test]
fn a_low_exponent_is_named_as_a_highlight_too_large() {
    let (g, words) = graded(&REFERENCE.replace("shininess = 64", "shininess = 8"));
    let top = &g.findings[0];
    assert_eq!(top.term, Term::Specular, "{words}");
    assert!(top.text.contains("specular highlight covers") && top.text.contains("exponent") && top.text.contains("too low"), "{words}");
    let ratio: f32 = top.text.split("covers ").nth(1).and_then(|t| t.split('×').next()).and_then(|t| t.parse().ok()).expect("a ratio");
    assert!(ratio > 3.0, "n = 8 against 64 spreads the highlight far wider: {ratio}");
    assert!(score(&g, Term::Specular).points < 20.0 && score(&g, Term::Diffuse).points == 20.0, "{words}");
    // ...and a high one as too small.
    let (_, words) = graded(&REFERENCE.replace("shininess = 64", "shininess = 1000"));
    assert!(words.contains("covers only") && words.contains("too high"), "{words}");
}

#[test]
fn a_missing_ambient_term_is_named() {
    let text = REFERENCE.replace("ambient = 0.15", "ambient = 0.0");
    let (g, words) = graded(&text);
    assert!(g.findings.iter().any(|f| f.term == Term::Ambient && f.text.starts_with("the ambient term is missing")), "{words}");
    assert_eq!(score(&g, Term::Ambient).points, 0.0, "{words}");
    assert!(score(&g, Term::Diffuse).points == 20.0 && score(&g, Term::Specular).points == 20.0, "{words}");
}

#[test]
fn a_light_in_the_wrong_place_is_named_with_where_it_lights() {
    let (g, words) = graded(&REFERENCE.replace("position = [2.5, 4.0, 2.0]", "position = [-2.5, 4.0, 2.0]"));
    let f = g.findings.iter().find(|f| f.term == Term::Diffuse).expect("a diffuse finding");
    assert!(f.text.contains("a light is in the wrong place") && f.text.contains("left"), "{words}");
    // The shadow moved to the other side too.
    assert!(g.findings.iter().any(|f| f.term == Term::Shadows && f.text.contains("different place")), "{words}");
    assert!(!g.passed || g.points < 80.0, "{words}");
}

#[test]
fn an_unclamped_n_dot_l_is_named() {
    let (g, words) = graded(&REFERENCE.replace("shininess = 64", "shininess = 64\nclamp_n_dot_l = false"));
    let f = g.findings.iter().find(|f| f.term == Term::Diffuse).expect("a diffuse finding");
    assert!(f.text.contains("N·L is not clamped"), "{words}");
    // A negative term develops to black like a zero one: the total is what loses points.
    assert!(score(&g, Term::Total).points < 25.0 && f.lost > 0.0, "{words}");
}

#[test]
fn shadows_turned_off_and_a_darker_diffuse_are_named() {
    let (g, words) = graded(&format!("{REFERENCE}shadows = \"none\"\n"));
    assert!(g.findings.iter().any(|f| f.term == Term::Shadows && f.text.contains("yours none")), "{words}");
    assert_eq!(score(&g, Term::Shadows).points, 0.0);
    let (_, words) = graded(&REFERENCE.replace("diffuse = [0.7, 0.1, 0.1]", "diffuse = [0.35, 0.05, 0.05]"));
    assert!(words.contains("the diffuse term is 0.5") && words.contains("`diffuse` (K_diff)"), "{words}");
}
