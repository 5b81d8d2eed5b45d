//! The live lab on a lesson's page: the controls generated from the lesson (each value's
//! range is the validator's, from [`crate::lesson::checked_values`]), the lesson's text and
//! files for the WebAssembly renderer, and the page's script. The renderer itself is built by
//! `tools/build-live.sh` (wasm-bindgen); the site copies it in when it is given one.

use crate::lesson::path::{KeyPath, Segment};
use crate::lesson::{CheckedValue, Lesson};
use base64::Engine as _;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// The page script: builds the controls, calls the renderer, draws the canvases.
pub const LAB_JS: &str = include_str!("lab.js");

/// The live lab's built files in `dir`: the wasm-bindgen glue and the module.
#[derive(Debug, Clone, PartialEq)]
pub struct LiveBuild {
    /// `shadelab_wasm.js` (wasm-bindgen `--target no-modules`).
    pub glue: String,
    /// `shadelab_wasm_bg.wasm` as a script that sets `SHADELAB_WASM` to its base64 bytes: a
    /// `<script src>` loads from `file://` too, where a page may not fetch a `.wasm` file.
    /// Encoded once, when read: `watch --serve` writes the pages again after every save.
    pub wasm_script: String,
}

impl LiveBuild {
    /// Reads the build from `dir`.
    ///
    /// # Errors
    /// A message naming the missing file and how to build it.
    pub fn read(dir: &Path) -> Result<LiveBuild, String> {
        let read = |name: &str| {
            std::fs::read(dir.join(name)).map_err(|e| {
                format!(
                    "{}: {}\n  hint: build the live lab with tools/build-live.sh (it writes target/live/)",
                    dir.join(name).display(),
                    crate::output::io_reason(&e)
                )
            })
        };
        let glue = String::from_utf8_lossy(&read("shadelab_wasm.js")?).into_owned();
        let wasm = read("shadelab_wasm_bg.wasm")?;
        let wasm_script = format!("window.SHADELAB_WASM = \"{}\";\n", base64::engine::general_purpose::STANDARD.encode(wasm));
        Ok(LiveBuild { glue, wasm_script })
    }
}

/// Where the lesson page's controls come from: one entry per value the reader may change.
///
/// - a material's number: a slider over the validator's range (logarithmic when the range
///   spans decades, cut to a useful window around the value);
/// - a colour: a picker (sRGB hex, decoded to linear by the validator as any text colour);
/// - a light's direction: azimuth and elevation;
/// - a choice (interpolation, shadows, tone map...): a menu of the allowed names;
/// - a whole-number render key (map size, samples): a menu of powers of two in range.
///
/// # Errors
/// The lesson's validation error (it was valid when loaded, so only on a changed file).
pub fn controls(lesson: &Lesson) -> Result<Vec<Value>, crate::lesson::LessonError> {
    // A key checked twice keeps its place and its last check: a colour is checked as three
    // numbers, then as a colour.
    let mut checked: Vec<crate::lesson::Checked> = Vec::new();
    for c in crate::lesson::checked_values(&lesson.source, &lesson.path, &lesson.overrides)? {
        match checked.iter_mut().find(|k| k.key == c.key) {
            Some(k) => *k = c,
            None => checked.push(c),
        }
    }
    // Only what the picture shows: the materials its objects wear (a lesson may define
    // materials for its figures alone), and no rasterizer key when the path tracer renders.
    let worn: Vec<String> = lesson
        .objects
        .iter()
        .map(|o| format!("material.{}.", KeyPath(vec![Segment::Key(lesson.materials[o.material].name.clone())])))
        .collect();
    let path_traced = lesson.scene.settings.method == crate::lesson::settings::RenderMethod::Path;
    let mut out = Vec::new();
    for c in checked {
        let group = c.key.split('.').next().unwrap_or("");
        if !matches!(group, "material" | "light" | "render")
            || (group == "material" && !worn.iter().any(|w| c.key.starts_with(w.as_str())))
            || (path_traced && matches!(c.key.as_str(), "render.interpolation" | "render.shadows" | "render.shadow_map_size"))
        {
            continue;
        }
        // Keys that change the scene's shape or the picture's frame are not the lab's.
        let last = c.key.rsplit('.').next().unwrap_or("");
        if matches!(last, "model" | "kind" | "aa" | "exposure" | "method" | "sampler" | "path" | "position" | "target" | "up") {
            continue;
        }
        let label = c.key.clone();
        match c.value {
            CheckedValue::Number { value, lo, hi, integer: true } if group == "render" || last == "samples" => {
                let mut names: Vec<i64> = (0..31).map(|k| 1i64 << k).filter(|&v| v as f64 >= lo && v as f64 <= hi.min(16384.0)).collect();
                let v = value as i64;
                if !names.contains(&v) {
                    names.push(v);
                    names.sort_unstable();
                }
                let names: Vec<String> = names.iter().map(|n| n.to_string()).collect();
                out.push(json!({"kind": "choice", "key": c.key, "label": label, "value": v.to_string(), "names": names}));
            }
            CheckedValue::Number { value, lo, hi, integer } => {
                let (min, max, log) = slider_range(value, lo, hi);
                out.push(json!({"kind": "number", "key": c.key, "label": label, "value": value, "min": min, "max": max, "log": log, "integer": integer}));
            }
            // A picker gives 0 to 1 a channel: offered where that is allowed and holds the value.
            CheckedValue::Colour { value, lo, hi } if lo <= 0.0 && hi >= 1.0 && value.iter().all(|c| (0.0..=1.0).contains(c)) => {
                out.push(json!({"kind": "colour", "key": c.key, "label": label, "value": value}));
            }
            CheckedValue::Vector { value, .. } if last == "direction" => {
                out.push(json!({"kind": "direction", "key": c.key, "label": label, "value": value}));
            }
            CheckedValue::Choice { value, names } if group == "render" || names.len() > 1 => {
                out.push(json!({"kind": "choice", "key": c.key, "label": label, "value": value, "names": names}));
            }
            _ => {}
        }
    }
    Ok(out)
}

/// A slider's (min, max, logarithmic) for `value` allowed in `lo..=hi`: the whole range when
/// it is short (roughness 0–1), else a window of two decades around the value, on a
/// logarithmic scale (shininess 32 gets 1.6–640 of its 0–10⁶).
fn slider_range(value: f64, lo: f64, hi: f64) -> (f64, f64, bool) {
    if hi - lo <= 10.0 {
        return (lo, hi, false);
    }
    if value <= 0.0 {
        return (lo.max(0.0), hi.min(10.0), false);
    }
    let min = (value / 20.0).max(lo).max(1e-3);
    let max = (value * 20.0).min(hi).max(min * 10.0).min(hi);
    (min, max, true)
}

/// The lesson's script for the page: its text, where it reads from, its files (base64) and
/// its controls, as `SHADELAB_LESSON`.
///
/// # Errors
/// A message when a file the lesson reads cannot be read.
pub fn lesson_script(lesson: &Lesson, stem: &str, controls: &[Value]) -> Result<String, String> {
    // The lesson as the browser names it: `lessons/<stem>.toml`, its files beside it.
    let folder = lesson.path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let root = crate::files::canonicalize(folder).unwrap_or_else(|_| folder.to_path_buf());
    let mut files = serde_json::Map::new();
    for f in lesson.asset_files() {
        let rel = f.strip_prefix(&root).map(Path::to_path_buf).unwrap_or_else(|_| PathBuf::from(f.file_name().unwrap_or_default()));
        let bytes = crate::files::read(&f).map_err(|e| format!("{}: {}", f.display(), crate::output::io_reason(&e)))?;
        let name = format!("lessons/{}", rel.to_string_lossy().replace('\\', "/"));
        files.insert(name, Value::String(base64::engine::general_purpose::STANDARD.encode(bytes)));
    }
    let data = json!({
        "path": format!("lessons/{stem}.toml"),
        "text": lesson.source,
        "sets": lesson.overrides.iter().map(|o| o.arg.clone()).collect::<Vec<_>>(),
        "size": [lesson.scene.camera.width, lesson.scene.camera.height],
        "method": crate::lesson::settings::RenderMethod::NAMES.iter().find(|(_, m)| *m == lesson.scene.settings.method).map_or("raster", |(n, _)| n),
        "files": files,
        "controls": controls,
    });
    // `</` cannot close a script element from inside a JSON string.
    Ok(format!("window.SHADELAB_LESSON = {};\n", data.to_string().replace("</", "<\\/")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_what_the_picture_shows_is_offered() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        // Lesson 09's named NDF materials are its figures' alone; its sphere wears `plastic`.
        let lesson = crate::lesson::load(&root.join("lessons/09-microfacet-ndfs.toml"), &[]).unwrap();
        let keys: Vec<String> = controls(&lesson).unwrap().iter().map(|c| c["key"].as_str().unwrap().to_string()).collect();
        assert!(keys.iter().any(|k| k == "material.plastic.roughness"), "{keys:?}");
        assert!(!keys.iter().any(|k| k.starts_with("material.GGX.")), "{keys:?}");
        // The path tracer reads no rasterizer key, and offers its own.
        let lesson = crate::lesson::load(&root.join("lessons/42-rasterizer-vs-path-tracer.toml"), &[]).unwrap();
        let keys: Vec<String> = controls(&lesson).unwrap().iter().map(|c| c["key"].as_str().unwrap().to_string()).collect();
        assert!(!keys.iter().any(|k| k == "render.interpolation" || k == "render.shadows"), "{keys:?}");
        assert!(keys.iter().any(|k| k == "render.spp"), "{keys:?}");
    }

    #[test]
    fn slider_ranges_stay_inside_the_validators() {
        assert_eq!(slider_range(0.3, 0.0, 1.0), (0.0, 1.0, false));
        let (min, max, log) = slider_range(32.0, 0.0, 1e6);
        assert!(log && (min - 1.6).abs() < 1e-9 && (max - 640.0).abs() < 1e-9);
        let (min, max, _) = slider_range(5e5, 0.0, 1e6);
        assert!(min >= 0.0 && max <= 1e6 && min < max);
        assert_eq!(slider_range(0.0, 0.0, 1e6), (0.0, 10.0, false));
    }

    #[test]
    fn lesson_one_offers_its_materials_lights_and_render_choices() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let lesson = crate::lesson::load(&root.join("lessons/01-first-light.toml"), &[]).unwrap();
        let c = controls(&lesson).unwrap();
        let find = |key: &str| c.iter().find(|v| v["key"] == key).unwrap_or_else(|| panic!("no control for {key}: {c:#?}"));
        assert_eq!(find("material.plastic.shininess")["kind"], "number");
        assert_eq!(find("material.plastic.diffuse")["kind"], "colour");
        assert_eq!(find("light.0.intensity")["kind"], "number");
        let interp = find("render.interpolation");
        assert_eq!(interp["kind"], "choice");
        assert!(interp["names"].as_array().unwrap().iter().any(|n| n == "gouraud"), "{interp}");
        assert_eq!(find("render.shadow_map_size")["value"], "1024", "a default is offered too");
        // Every number's slider lies inside the validator's range: the end points validate.
        for v in c.iter().filter(|v| v["kind"] == "number") {
            for end in ["min", "max"] {
                let set = crate::lesson::Override::parse(&format!("{}={}", v["key"].as_str().unwrap(), v[end])).unwrap();
                crate::lesson::parse(&lesson.source, &lesson.path, &[set]).unwrap_or_else(|e| panic!("{} at its {end}: {e}", v["key"]));
            }
        }
    }
}
