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
