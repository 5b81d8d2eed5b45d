//! `shadelab grade`: exit codes, the Markdown report and its images, the JUnit entry, and a
//! failed grade (never a crash) for a student lesson that cannot be graded.

use crate::helpers::{lessons_dir, shadelab};
use std::path::Path;

const REFERENCE: &str = r#"
[camera]
position = [0.0, 3.0, 5.0]
look_at = [0.0, 0.4, 0.0]
fov_deg = 40.0
size = [80, 80]

[[object]]
shape = "plane"
scale = 3
material = "floor"

[[object]]
shape = "uv_sphere"
translate = [0.0, 1.0, 0.0]
material = "plastic"

[material.floor]
model = "lambert"
diffuse = 0.6

[material.plastic]
model = "phong"
diffuse = [0.7, 0.1, 0.1]
specular = 0.6
shininess = 64

[[light]]
kind = "point"
position = [2.5, 4.0, 2.0]

[scene]
ambient = 0.15

[[figure]]
name = "terms"
kind = "split"
layers = ["ambient", "diffuse", "specular"]
"#;

/// A folder with the reference and `student` (as student.toml).
fn course(student: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("reference.toml"), REFERENCE).unwrap();
    std::fs::write(dir.path().join("student.toml"), student).unwrap();
    dir
}

fn grade(dir: &Path, extra: &[&str]) -> assert_cmd::assert::Assert {
    shadelab().arg("grade").arg(dir.join("student.toml")).arg("--against").arg(dir.join("reference.toml")).args(extra).assert()
}

/// (tests, failures) of a JUnit document, from both the attributes and the elements.
fn junit_counts(xml: &str) -> (usize, usize) {
    let attr = |name: &str| -> usize {
        let at = xml.find(&format!(" {name}=\"")).unwrap_or_else(|| panic!("no {name}= in\n{xml}")) + name.len() + 3;
        xml[at..].split('"').next().unwrap().parse().unwrap()
    };
    let (tests, failures) = (attr("tests"), attr("failures"));
    assert_eq!(xml.matches("<testcase ").count(), tests, "{xml}");
    assert_eq!(xml.matches("<failure ").count(), failures, "{xml}");
    (tests, failures)
}

#[test]
fn the_reference_passes_with_every_point_and_a_wrong_exponent_fails_named() {
    let dir = course(REFERENCE);
    let a = grade(dir.path(), &[]).success();
    let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(stdout.starts_with("grade: 100 of 100 points (pass mark 60): passed"), "{stdout}");
    // Rubric: the specular term weighs 80 and the pass mark is 90, so the exponent decides.
    std::fs::write(dir.path().join("rubric.toml"), "pass = 90\n[term.specular]\nweight = 80\n").unwrap();
    std::fs::write(dir.path().join("student.toml"), REFERENCE.replace("shininess = 64", "shininess = 6")).unwrap();
    let out = dir.path().join("report");
    let junit = dir.path().join("junit.xml");
    let a = grade(dir.path(), &["--rubric", &dir.path().join("rubric.toml").to_string_lossy(), "-o"]).get_output().clone();
    assert_eq!(a.status.code(), Some(2), "-o without a folder is a usage error");
    let a = shadelab()
        .arg("grade")
        .arg(dir.path().join("student.toml"))
        .arg("--against")
        .arg(dir.path().join("reference.toml"))
        .arg("--rubric")
        .arg(dir.path().join("rubric.toml"))
        .arg("-o")
        .arg(&out)
        .arg("--junit")
        .arg(&junit)
        .assert()
        .code(1);
    let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(stdout.contains("of 160 points (pass mark 90): failed"), "{stdout}");
    assert!(stdout.contains("specular") && stdout.contains("exponent (`shininess`, K_shi) is too low"), "{stdout}");
    // The Markdown: the finding first, and every image it shows exists, is a PNG of the render's size.
    let md = std::fs::read_to_string(out.join("grade.md")).unwrap();
    assert!(md.find("too low").unwrap() < md.find("## Points").unwrap(), "{md}");
    let images: Vec<&str> = md.split("](").skip(1).map(|s| s.split(')').next().unwrap()).collect();
    assert!(images.len() >= 12 && images.contains(&"images/specular-flip.png"), "{images:?}");
    for i in &images {
        let img = image::open(out.join(i)).unwrap_or_else(|e| panic!("{i}: {e}"));
        assert_eq!((img.width(), img.height()), (80, 80), "{i}");
    }
    // JUnit: a test per term and the grade; the specular one and the grade fail.
    let xml = std::fs::read_to_string(&junit).unwrap();
    let (tests, failures) = junit_counts(&xml);
    assert_eq!(tests, 9, "{xml}");
    assert!(failures >= 2 && xml.contains("name=\"specular\" time=\"0.000\">") && xml.contains("type=\"grade\""), "{xml}");
}

#[test]
fn a_student_lesson_that_cannot_be_graded_is_a_failed_grade_with_the_reason() {
    for (student, why) in [
        (REFERENCE.replace("shininess = 64", "shininess = -1"), "student.toml:"),
        (REFERENCE.replace("size = [80, 80]", "size = [64, 80]"), "your image is 64×80 pixels, the reference's 80×80"),
        (REFERENCE.replace("shape = \"plane\"", "shape = \"mesh\"\npath = \"../outside.obj\""), "outside the lesson's folder"),
        ("not toml [".to_string(), "student.toml:"),
    ] {
        let dir = course(&student);
        let junit = dir.path().join("j.xml");
        let a = grade(dir.path(), &["--junit", &junit.to_string_lossy(), "-o", &dir.path().join("r").to_string_lossy()]).code(1);
        let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
        let stderr = String::from_utf8_lossy(&a.get_output().stderr).into_owned();
        assert!(stdout.starts_with("grade: 0 of 100 points") && stdout.contains(why), "{why}:\n{stdout}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert_eq!(junit_counts(&std::fs::read_to_string(&junit).unwrap()), (1, 1));
        assert!(std::fs::read_to_string(dir.path().join("r/grade.md")).unwrap().contains(why));
    }
}

#[test]
fn a_wrong_reference_rubric_or_figure_is_bad_input() {
    let dir = course(REFERENCE);
    std::fs::write(dir.path().join("reference.toml"), REFERENCE.replace("shininess = 64", "shininess = -1")).unwrap();
    let a = grade(dir.path(), &[]).code(2);
    assert!(String::from_utf8_lossy(&a.get_output().stderr).contains("reference.toml:"));
    let dir = course(REFERENCE);
    std::fs::write(dir.path().join("r.toml"), "[term.glossy]\nweight = 3\n").unwrap();
    let a = grade(dir.path(), &["--rubric", &dir.path().join("r.toml").to_string_lossy()]).code(2);
    assert!(String::from_utf8_lossy(&a.get_output().stderr).contains("unknown term"));
    let a = grade(dir.path(), &["--figure", "nope"]).code(2);
    assert!(String::from_utf8_lossy(&a.get_output().stderr).contains("its figures are terms"));
}

#[test]
fn a_figure_is_graded_beside_the_terms() {
    let dir = course(&REFERENCE.replace("diffuse = [0.7, 0.1, 0.1]", "diffuse = [0.1, 0.1, 0.7]"));
    let out = dir.path().join("r");
    let a = grade(dir.path(), &["--figure", "terms", "-o", &out.to_string_lossy()]);
    let stdout = String::from_utf8_lossy(&a.get_output().stdout).into_owned();
    assert!(stdout.contains(" of 120 points") && stdout.contains("\n  figure "), "{stdout}");
    assert!(stdout.contains("the figure `terms` differs most"), "{stdout}");
    assert!(out.join("images/figure-flip.png").is_file());
    // A bundled lesson against itself, figure and all: every point.
    let lesson = lessons_dir().join("04-shininess.toml");
    let a = shadelab().arg("grade").arg(&lesson).arg("--against").arg(&lesson).args(["--figure", "sweep"]).assert().success();
    assert!(String::from_utf8_lossy(&a.get_output().stdout).starts_with("grade: 120 of 120 points"));
}
