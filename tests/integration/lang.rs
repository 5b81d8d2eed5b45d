//! `--lang ja` and `[lesson] lang`: built-in text in the course's Japanese terms, English
//! unchanged.

use crate::helpers::{lessons_dir, shadelab};

fn explain(extra: &[&str]) -> String {
    let out = shadelab().arg("explain").arg(lessons_dir().join("01-first-light.toml")).args(extra).assert().success();
    String::from_utf8(out.get_output().stdout.clone()).unwrap()
}

#[test]
fn explain_speaks_japanese_with_lang_ja_and_english_otherwise() {
    let en = explain(&[]);
    for word in ["Materials", "Lights", "Passes", "runs", "skipped", "What ran (one render", "samples shaded (visible, once each)"] {
        assert!(en.contains(word), "English lacks {word:?}\n{en}");
    }
    let ja = explain(&["--lang", "ja"]);
    for word in ["材質", "光源", "パス", "実行", "省略", "実行されたもの (1 回の描画", "シェーディングしたサンプル"]
    {
        assert!(ja.contains(word), "Japanese lacks {word:?}\n{ja}");
    }
    for word in ["Materials", "Passes", "What ran", "samples shaded"] {
        assert!(!ja.contains(word), "Japanese still says {word:?}\n{ja}");
    }
    // Columns line up: a CJK character takes two terminal columns, so the count after
    // "入力三角形" (5 characters, 10 columns) starts where the English one does.
    let column = |text: &str, label: &str| {
        let line = text.lines().find(|l| l.trim_start().starts_with(label)).unwrap_or_else(|| panic!("no {label}"));
        let width: usize = line.chars().map(|c| if c > '\u{1100}' { 2 } else { 1 }).sum();
        width
    };
    assert_eq!(column(&ja, "入力三角形"), column(&en, "triangles in"));
    // `[lesson] lang` does the same as the flag.
    assert_eq!(explain(&["--set", "lesson.lang=\"ja\""]).lines().nth(2), ja.lines().nth(2));
}

/// Whether `s` reads the same in both languages: no Latin word but course notation (`K_shi`,
/// `GGX`, `RMSE`, units, function names) once quoted identifiers are set aside.
fn is_notation(s: &str) -> bool {
    // Names the lectures keep in Latin letters too (`V-cavity`, `Sobol`, `Burley`, `Jensen`).
    const NOTATION: [&str; 44] = [
        "Burley", "Jensen", "GGX", "RMSE", "PSNR", "dB", "ms", "SH", "IBL", "BRDF", "BSDF", "BTDF", "NDF", "PCF", "AgX", "ACES", "CMJ",
        "HDR", "sRGB", "aa", "spp", "sr", "cos", "sin", "tan", "ln", "exp", "log", "max", "min", "mix", "arcsin", "obj", "png", "glb",
        "UV", "ICO", "BVH", "RGB", "XYZ", "mm", "nm", "Sobol", "cavity",
    ];
    // File names (`cube.obj`) are the files' names.
    let s: Vec<&str> = s.split(' ').filter(|w| !w.ends_with(".obj") && !w.ends_with(".glb") && !w.ends_with(".png")).collect();
    let mut rest = String::new();
    let mut quoted = false;
    for c in s.join(" ").chars() {
        if c == '"' || c == '`' {
            quoted = !quoted;
        } else if !quoted {
            rest.push(c);
        }
    }
    // `K_shi`, `L_{spot}`, `sigma_s`: a subscripted symbol is notation, letters and all.
    let words: Vec<&str> = rest.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).collect();
    words.iter().all(|w| {
        let letters = w.chars().filter(char::is_ascii_alphabetic).count();
        // Short capitals are symbols (`FL` in L = E + ρFL, `RGB`).
        let symbol = w.len() <= 3 && w.chars().all(|c| c.is_ascii_uppercase() || c.is_ascii_digit());
        letters < 2 || symbol || w.contains('_') || NOTATION.contains(w)
    })
}

/// Every text a lesson gives (`[lesson]` title, summary and notes; a figure's title, caption
/// and labels) under `at`, each a table with both languages, or plain notation.
fn untranslated(at: &str, v: &toml::Value, out: &mut Vec<String>) {
    match v {
        toml::Value::Table(t)
            if !(t.get("en").is_some_and(toml::Value::is_str)
                && t.get("ja").is_some_and(|j| j.as_str().is_some_and(|j| !j.trim().is_empty()))) =>
        {
            out.push(format!("{at}: {v} (needs both `en` and `ja`)"));
        }
        toml::Value::String(s) if !is_notation(s) => out.push(format!("{at}: {s:?} (English only; give {{ en, ja }})")),
        _ => {}
    }
}

#[test]
fn every_bundled_lesson_speaks_both_languages() {
    let mut missing = Vec::new();
    let mut lessons = 0;
    for entry in std::fs::read_dir(lessons_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        lessons += 1;
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let doc: toml::Table = std::fs::read_to_string(&path).unwrap().parse().unwrap();
        let info = doc["lesson"].as_table().unwrap();
        for key in ["title", "summary", "notes"] {
            match info.get(key) {
                Some(v) => untranslated(&format!("{name} [lesson] {key}"), v, &mut missing),
                None => missing.push(format!("{name} [lesson] has no {key}")),
            }
        }
        for fig in doc.get("figure").and_then(toml::Value::as_array).into_iter().flatten() {
            let at = format!("{name} figure {}", fig["name"]);
            for key in ["title", "caption"] {
                if let Some(v) = fig.get(key) {
                    untranslated(&format!("{at} {key}"), v, &mut missing);
                }
            }
            let axes = [Some(fig), fig.get("rows"), fig.get("cols")];
            for labels in axes.into_iter().flatten().filter_map(|a| a.get("labels")).filter_map(toml::Value::as_array) {
                for (i, l) in labels.iter().enumerate() {
                    untranslated(&format!("{at} labels.{i}"), l, &mut missing);
                }
            }
            if let Some(bar) = fig.get("colorbar").and_then(|c| c.get("label")) {
                untranslated(&format!("{at} colorbar.label"), bar, &mut missing);
            }
        }
    }
    assert!(lessons >= 38, "{lessons} lessons");
    assert!(missing.is_empty(), "{} texts without Japanese:\n{}", missing.len(), missing.join("\n"));
    // The check can fail: English prose is caught, notation is not.
    assert!(!is_notation("roughness = 0.05") && !is_notation("the reference") && !is_notation("naive 32"));
    assert!(is_notation("K_shi = 50") && is_notation("RMSE 1.2e-3 · PSNR 40 dB") && is_notation("θ = 30°, cos θ = 0.87"));
}

#[test]
fn the_gallery_in_japanese_leaves_no_built_in_english() {
    let out = tempfile::tempdir().unwrap();
    let log = out.path().join("drawn.txt");
    // Small cells: the words are what is checked, not the pictures.
    shadelab()
        .env("SHADELAB_TEXT_LOG", &log)
        .args(["figures", "--lang", "ja", "--cell", "48x48", "--scale", "0.5", "-q", "-o"])
        .arg(out.path().join("figures"))
        .arg(lessons_dir())
        .assert()
        .success();
    // The lessons' own words (titles, captions, labels, material names) are the lessons'
    // business (the test above); what is left is text the program made.
    let mut own = String::new();
    for entry in std::fs::read_dir(lessons_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            own += &shadelab::figure::text::to_plain_text(&std::fs::read_to_string(&path).unwrap().replace("\\\"", "\""));
        }
    }
    let drawn = std::fs::read_to_string(&log).unwrap();
    let mut english: Vec<&str> = drawn.lines().map(str::trim).filter(|l| !is_notation(l) && !own.contains(*l)).collect();
    english.sort_unstable();
    english.dedup();
    assert!(drawn.lines().count() > 1000, "the log holds what was drawn");
    assert!(drawn.contains("精度と計算時間") && drawn.contains("グロー (Gouraud)"), "built-in Japanese is drawn");
    assert!(english.is_empty(), "{} lines stay English under --lang ja:\n{}", english.len(), english.join("\n"));
}
