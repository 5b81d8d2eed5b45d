//! The layers point downward only (docs/architecture.md, "Layers"): a module may name
//! `crate::X` only for an X ranked below it, in its code and in its unit tests alike
//! (a shading test builds its incidents itself, not from the scene's lights). Comments are
//! not code, so they are skipped.

use std::path::{Path, PathBuf};

/// Every top-level module, bottom first. Within layer 0 the order is strict too: shading
/// and raster sit below the lesson format, so they know nothing of files.
const ORDER: [(&str, u32); 21] = [
    ("simd", 0),
    ("geometry", 0),
    // Where input bytes come from: the file system, or memory in the WebAssembly build.
    ("files", 0),
    ("output", 0),
    // The on-disk cache of deterministic results, beside output: it knows bytes and keys only.
    ("cache", 0),
    ("shading", 0),
    ("raster", 0),
    ("lesson", 0),
    // Lights know their parameters, incidents, samples and shadow-method choice, built from
    // the lesson's validated `LightSpec`; the scene holds them (DESIGN.md: layer 1).
    ("light", 1),
    ("scene", 1),
    // The plan (in render) asks each effect whether it is needed, so effects sit below render.
    ("effects", 2),
    // The per-point integrator and the ray-query service: it reads the effects' passes
    // (maps, prefiltered environments, probes) and the pipeline in render asks it.
    ("transport", 2),
    ("render", 2),
    ("bridge", 3),
    ("cost", 3),
    ("figure", 3),
    // Grading renders two lessons and compares them with ꟻLIP (cost::flip).
    ("grade", 3),
    ("bench", 3),
    ("site", 4),
    ("cli", 5),
    ("main", 5),
];

fn rank(module: &str) -> Option<usize> {
    ORDER.iter().position(|(m, _)| *m == module)
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// `(line number, target module)` for every `crate::X` in the code of `source`.
fn crate_paths(source: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (i, line) in source.lines().enumerate() {
        let code = line.trim_start();
        if code.starts_with("//") {
            continue;
        }
        let code = code.split(" // ").next().unwrap_or(code);
        for (at, _) in code.match_indices("crate::") {
            // `supercrate::` or `shadelab_crate::` are not paths of this crate.
            if at > 0 && code[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
                continue;
            }
            let target: String = code[at + 7..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            found.push((i + 1, target));
        }
    }
    found
}

#[test]
fn every_crate_path_points_down_the_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut upward = Vec::new();
    let mut unknown = Vec::new();
    for file in &files {
        let relative = file.strip_prefix(&src).unwrap();
        let first = relative.components().next().unwrap().as_os_str().to_string_lossy().to_string();
        let module = first.trim_end_matches(".rs").to_string();
        if module == "lib" {
            continue;
        }
        let Some(from) = rank(&module) else {
            unknown.push(format!("src/{}: module `{module}` has no layer in ORDER", relative.display()));
            continue;
        };
        for (line, target) in crate_paths(&std::fs::read_to_string(file).unwrap()) {
            match rank(&target) {
                Some(to) if to > from => upward.push(format!(
                    "src/{}:{line}: `{module}` (layer {}) uses `crate::{target}` (layer {})",
                    relative.display(),
                    ORDER[from].1,
                    ORDER[to].1
                )),
                Some(_) => {}
                None => unknown.push(format!("src/{}:{line}: `crate::{target}` is no module in ORDER", relative.display())),
            }
        }
    }
    assert!(unknown.is_empty(), "modules without a layer:\n{}", unknown.join("\n"));
    assert!(upward.is_empty(), "{} imports point up the layers:\n{}", upward.len(), upward.join("\n"));
}

#[test]
fn the_checker_sees_upward_paths_in_code_and_tests_but_not_in_comments() {
    let source = "use crate::scene::Light;\n// crate::cli in a comment\nlet x = crate::render::plan(s); // crate::cli\n#[cfg(test)]\nuse crate::cli::run;\n";
    let paths: Vec<String> = crate_paths(source).into_iter().map(|(_, t)| t).collect();
    assert_eq!(paths, ["scene", "render", "cli"]);
    assert!(rank("shading") < rank("lesson") && rank("lesson") < rank("light") && rank("light") < rank("scene"));
    assert!(rank("effects") < rank("transport") && rank("transport") < rank("render"));
    assert!(rank("figure") < rank("cli"));
}
