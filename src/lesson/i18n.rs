//! The language of built-in labels (`[lesson] lang`, `--lang`): English, or Japanese in the
//! course's terms. One table, keyed by the English text, which is the message id; English
//! is the default and its text is the id itself, so English output never changes.

/// A language for built-in labels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Lang {
    /// English (the default).
    #[default]
    En,
    /// Japanese.
    Ja,
}

impl Lang {
    /// The names lesson files and `--lang` use.
    pub const NAMES: [(&'static str, Lang); 2] = [("en", Lang::En), ("ja", Lang::Ja)];

    /// The name in lesson files.
    pub fn name(self) -> &'static str {
        match self {
            Lang::En => "en",
            Lang::Ja => "ja",
        }
    }

    /// `text` (a built-in English label, the message id) in this language; text the table
    /// does not hold is returned as it is.
    pub fn tr(self, text: &str) -> &str {
        match self {
            Lang::En => text,
            Lang::Ja => JA.iter().find(|(en, _)| *en == text).map_or(text, |(_, ja)| ja),
        }
    }
}

/// English → Japanese, in the course's terms (環境光反射成分, 拡散反射成分, 鏡面反射成分).
const JA: &[(&str, &str)] = &[
    // Split layers.
    ("Ambient", "環境光"),
    ("Diffuse", "拡散反射"),
    ("Specular", "鏡面反射"),
    ("Emission", "放射"),
    ("Reflection", "映り込み"),
    ("Total", "合計"),
    ("Normal", "法線"),
    // Interpolation, models, light kinds as column labels.
    ("Flat", "フラット"),
    ("Gouraud", "グーロー"),
    ("Phong", "フォン"),
    ("Blinn-Phong", "ブリン・フォン"),
    ("Lambert", "ランバート"),
    ("Screen", "スクリーン空間"),
    ("Perspective", "透視補正"),
    ("Point", "点光源"),
    ("Directional", "平行光源"),
    ("Spot", "スポットライト"),
    // Terms of the illumination equation.
    ("ambient term", "環境光反射成分"),
    ("diffuse term", "拡散反射成分"),
    ("specular term", "鏡面反射成分"),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn english_is_the_id_and_japanese_uses_the_course_terms() {
        assert_eq!(Lang::En.tr("Diffuse"), "Diffuse");
        assert_eq!(Lang::Ja.tr("Ambient"), "環境光");
        assert_eq!(Lang::Ja.tr("Diffuse"), "拡散反射");
        assert_eq!(Lang::Ja.tr("Specular"), "鏡面反射");
        assert_eq!(Lang::Ja.tr("Total"), "合計");
        assert_eq!(Lang::Ja.tr("Gouraud"), "グーロー");
        assert_eq!(Lang::Ja.tr("specular term"), "鏡面反射成分");
        assert_eq!(Lang::Ja.tr("K_shi = 50"), "K_shi = 50", "notation is not translated");
        // Every id is listed once.
        for (i, (en, _)) in JA.iter().enumerate() {
            assert!(!JA[..i].iter().any(|(e, _)| e == en), "{en} twice");
        }
    }
}
