//! Colours written as text: sRGB hex (`"#cc1111"`, `"#c11"`) and the CSS colour names
//! (`"blue"`, `"rebeccapurple"`), decoded once, at load, to the linear RGB the renderer uses.
//!
//! The names and their sRGB bytes are the 148 named colours of CSS Color Module Level 4
//! (§6.1, <https://www.w3.org/TR/css-color-4/#named-colors>), taken from the
//! `csscolorparser` crate's table. Decoding is the exact sRGB EOTF of IEC 61966-2-1:
//! `c ≤ 0.04045 → c / 12.92`, else `((c + 0.055) / 1.055)^2.4`.

use glam::Vec3;

/// Why a colour string could not be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ColorTextError {
    /// Starts with `#` but is not `#rgb` or `#rrggbb` hex.
    BadHex,
    /// Not a CSS colour name; the closest name, if one is close.
    UnknownName(Option<&'static str>),
}

/// The sRGB electro-optical transfer function (IEC 61966-2-1): encoded `c` in [0, 1] → linear.
pub fn srgb_to_linear(c: f64) -> f64 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// Every CSS colour name, lower case, in the standard's order.
pub fn names() -> Vec<&'static str> {
    csscolorparser::NAMED_COLORS.keys().map(|k| k.as_str()).collect()
}

/// The linear RGB of `"#rgb"`, `"#rrggbb"` or a CSS colour name (any case, spaces around ignored).
///
/// # Errors
/// [`ColorTextError`] for malformed hex or an unknown name (with the nearest name).
pub fn parse(text: &str) -> Result<Vec3, ColorTextError> {
    let s = text.trim();
    let bytes = if let Some(hex) = s.strip_prefix('#') { hex_bytes(hex).ok_or(ColorTextError::BadHex)? } else { named(s)? };
    let lin = bytes.map(|b| srgb_to_linear(f64::from(b) / 255.0) as f32);
    Ok(Vec3::from(lin))
}

/// `rgb` or `rrggbb` hex digits as bytes (`#rgb` doubles each digit, as CSS does).
fn hex_bytes(hex: &str) -> Option<[u8; 3]> {
    if !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    let digit = |i: usize| u8::from_str_radix(&hex[i..=i], 16).ok();
    match hex.len() {
        3 => Some([digit(0)? * 17, digit(1)? * 17, digit(2)? * 17]),
        6 => {
            let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
            Some([byte(0)?, byte(2)?, byte(4)?])
        }
        _ => None,
    }
}

/// The sRGB bytes of a CSS colour name (case, spaces, `_` and `-` ignored: "Light Blue" = "lightblue").
fn named(name: &str) -> Result<[u8; 3], ColorTextError> {
    let key = name.to_ascii_lowercase().replace([' ', '_', '-'], "");
    let found = csscolorparser::NAMED_COLORS.entries().find(|(k, _)| k.as_str().eq_ignore_ascii_case(&key));
    match found {
        Some((_, rgb)) => Ok(*rgb),
        None => Err(ColorTextError::UnknownName(crate::lesson::suggest(&key, &names()))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The EOTF written out once more, in f64, for the expected values.
    fn eotf(byte: u8) -> f32 {
        let c = f64::from(byte) / 255.0;
        (if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }) as f32
    }

    #[test]
    fn hex_decodes_with_the_srgb_formula() {
        // #808080: 128/255 = 0.50196 → ((0.50196 + 0.055)/1.055)^2.4 = 0.21586.
        let g = parse("#808080").unwrap();
        assert!((g.x - 0.21586).abs() < 5e-6 && g == Vec3::splat(g.x), "{g}");
        // The linear segment: 10/255 = 0.0392 ≤ 0.04045 → 0.0392/12.92 = 0.003035.
        assert!((parse("#0a0a0a").unwrap().x - 10.0 / 255.0 / 12.92).abs() < 1e-7);
        let c = parse("#cc1111").unwrap();
        assert_eq!(c, Vec3::new(eotf(0xcc), eotf(0x11), eotf(0x11)));
        assert_eq!(parse("#c11").unwrap(), c, "#rgb doubles each digit");
        assert_eq!(parse("#FFFFFF").unwrap(), Vec3::ONE);
        assert_eq!(parse("#000").unwrap(), Vec3::ZERO);
        for bad in ["#12", "#1234", "#gg0000", "#", "#12345678"] {
            assert_eq!(parse(bad), Err(ColorTextError::BadHex), "{bad}");
        }
    }

    #[test]
    fn css_names_decode_and_unknown_names_get_the_nearest() {
        assert_eq!(names().len(), 148, "CSS Color 4 names 148 colours");
        assert_eq!(parse("blue").unwrap(), Vec3::new(0.0, 0.0, 1.0));
        assert_eq!(parse("Blue").unwrap(), parse("blue").unwrap());
        assert_eq!(parse("rebeccapurple").unwrap(), parse("#663399").unwrap());
        assert_eq!(parse("Light Blue").unwrap(), parse("#add8e6").unwrap());
        assert_eq!(parse("grey").unwrap(), parse("gray").unwrap());
        assert_eq!(parse("gold").unwrap(), Vec3::new(1.0, eotf(215), 0.0));
        assert_eq!(parse("bleu"), Err(ColorTextError::UnknownName(Some("blue"))));
        assert_eq!(parse("cornflowerblu"), Err(ColorTextError::UnknownName(Some("cornflowerblue"))));
        assert!(matches!(parse("zzzzzzzzzz"), Err(ColorTextError::UnknownName(None))));
    }
}
