//! The Japanese font the pages need, shipped with the site: a browser on a machine without a
//! CJK font (most CI runners, many lab PCs) would draw lesson 34's Japanese as empty boxes.
//! The embedded Noto Sans JP subset (`figure::text::cjk_font_bytes`) is cut down to the
//! characters the pages use and given a Unicode cmap, so a site with Japanese carries a few
//! kilobytes of font instead of 1.5 MB.

use ab_glyph::{Font, FontRef};
use allsorts::binary::read::ReadScope;
use allsorts::font_data::FontData;
use allsorts::subset::{CmapTarget, SubsetProfile, subset};

/// The family name the style sheet gives the shipped font.
pub const FAMILY: &str = "shadelab-ja";

/// The font file's name in the site folder.
pub const FILE: &str = "shadelab-ja.otf";

/// Whether the pages' font should carry `c`: CJK punctuation, kana, kanji and full-width
/// forms (the system's own font draws Latin, Greek and mathematical symbols).
fn wanted(c: char) -> bool {
    matches!(c as u32, 0x2E80..=0x9FFF | 0xF900..=0xFAFF | 0xFE30..=0xFE4F | 0xFF00..=0xFFEF)
}

/// The embedded Japanese font cut to the characters of `text` it has, or `None` when the
/// text has none (no font is shipped).
///
/// # Errors
/// A message when the subsetter fails (the embedded font is tested to subset).
pub fn subset_for(text: &str) -> Result<Option<(Vec<u8>, usize)>, String> {
    let data = crate::figure::text::cjk_font_bytes();
    let font = FontRef::try_from_slice(data).map_err(|e| format!("the embedded Japanese font: {e}"))?;
    let mut chars: Vec<char> = text.chars().filter(|&c| wanted(c)).collect();
    chars.sort_unstable();
    chars.dedup();
    // Glyph 0 (.notdef) first, as every font has it; then each character the font draws.
    let mut glyphs: Vec<u16> = vec![0];
    for c in &chars {
        let g = font.glyph_id(*c).0;
        if g != 0 && !glyphs.contains(&g) {
            glyphs.push(g);
        }
    }
    if glyphs.len() == 1 {
        return Ok(None);
    }
    let scope = ReadScope::new(data);
    let file = scope.read::<FontData<'_>>().map_err(|e| format!("the embedded Japanese font: {e}"))?;
    let provider = file.table_provider(0).map_err(|e| format!("the embedded Japanese font: {e}"))?;
    let bytes = subset(&provider, &glyphs, &SubsetProfile::Minimal, CmapTarget::Unicode)
        .map_err(|e| format!("cutting the Japanese font to the pages' characters: {e}"))?;
    Ok(Some((bytes, glyphs.len() - 1)))
}

/// The `@font-face` rule for the shipped font (prepended to the style sheet). The style sheet
/// names this family first: it holds no Latin, so Latin falls through to the system's font,
/// while Japanese never reaches `system-ui`, which under `lang="ja"` and a bold weight let
/// Chromium draw empty boxes even with this font loaded (seen on the h1 of lesson 34's page).
pub fn face_rule() -> String {
    format!("@font-face {{ font-family: \"{FAMILY}\"; src: url(\"{FILE}\") format(\"opentype\"); font-display: block; }}\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_subset_draws_exactly_the_pages_japanese() {
        let text = "影の向き — 拡散反射と鏡面反射 (Phong), 「合計」。ＡＢ";
        let (bytes, n) = subset_for(text).expect("subsets").expect("Japanese in the text");
        let font = FontRef::try_from_slice(&bytes).expect("the subset parses");
        for c in text.chars().filter(|&c| wanted(c)) {
            let g = font.glyph_id(c);
            assert!(g.0 != 0 && font.outline(g).is_some(), "{c} is drawn");
        }
        // Characters of the full font the pages do not use are gone; so is Latin.
        for c in ['光', '源', 'あ', 'A'] {
            assert_eq!(font.glyph_id(c).0, 0, "{c} was not asked for");
        }
        assert_eq!(n, text.chars().filter(|&c| wanted(c)).collect::<std::collections::BTreeSet<_>>().len());
        assert!(bytes.len() < 20_000, "{} bytes for {n} glyphs", bytes.len());
        assert!(subset_for("Phong, Blinn-Phong: (R·V)^n").unwrap().is_none(), "no Japanese, no font");
    }
}
