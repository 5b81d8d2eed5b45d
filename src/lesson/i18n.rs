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
    // `explain`: sections, decisions and counts.
    ("Materials", "材質"),
    ("Lights", "光源"),
    ("(none)", "(なし)"),
    ("Passes", "パス"),
    ("runs", "実行"),
    ("skipped", "省略"),
    ("shadows", "影"),
    ("What ran (one render", "実行されたもの (1 回の描画"),
    ("passes", "実行したパス"),
    ("Radiosity", "ラジオシティ"),
    ("triangles in", "入力三角形"),
    ("  clipped (near plane or guard band)", "  クリップ (ニア面・ガードバンド)"),
    ("  culled (back-facing)", "  カリング (裏向き)"),
    ("  outside the image", "  画像の外"),
    ("  degenerate (zero area)", "  縮退 (面積 0)"),
    ("samples rasterized (with overdraw)", "ラスタライズしたサンプル (重ね描き込み)"),
    ("samples shaded (visible, once each)", "シェーディングしたサンプル (可視, 各 1 回)"),
    ("vertices lit (Gouraud)", "照明計算した頂点 (グーロー)"),
    ("faces lit (flat)", "照明計算した面 (フラット)"),
    ("light evaluations", "光源の評価"),
    ("  of them per sample (Phong)", "  うちサンプルごと (フォン)"),
    ("diffuse-term evaluations", "拡散反射成分の評価"),
    ("specular-term evaluations", "鏡面反射成分の評価"),
    ("shadow rays traced", "シャドウレイ"),
    ("BVH nodes", "BVH ノード"),
    ("shadow-map texels written", "シャドウマップのテクセル"),
    ("shadow-map lookups", "シャドウマップの参照"),
    ("fog: samples marched or blended", "フォグ: 処理したサンプル"),
    ("fog: ray-march steps", "フォグ: レイマーチングのステップ"),
    ("probe capture: cube-map texels rendered", "プローブ: 描画したキューブマップのテクセル"),
    ("radiosity patches", "ラジオシティのパッチ"),
    ("radiosity form factors (non-zero)", "フォームファクター (非 0)"),
    ("radiosity iterations", "ラジオシティの反復"),
    ("NaN samples (replaced by 0)", "NaN のサンプル (0 に置換)"),
    // Figures: default titles and row labels.
    ("BRDF lobe: f·cos θₒ in the plane of incidence", "BRDF のローブ: 入射面内の f·cos θₒ"),
    ("Spot distribution: C_spot(θ) from the spot's axis", "スポットライトの配光: 軸からの角 θ の C_spot(θ)"),
    ("Directional albedo (white furnace)", "方向アルベド (ホワイトファーネス)"),
    ("What accuracy costs", "精度と計算時間"),
    ("ladder", "段階"),
    ("render", "描画"),
    ("error", "誤差"),
    ("|difference|", "|差|"),
    ("the reference", "基準"),
    // `cost` table headers.
    ("rung", "段"),
    ("triangles", "三角形"),
    ("median ms", "中央値 ms"),
    ("min ms", "最小 ms"),
    ("max ms", "最大 ms"),
    ("max err", "最大誤差"),
    ("visible %", "可視 %"),
    ("front", "パレート"),
    ("reference", "基準"),
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
        assert_eq!(Lang::Ja.tr("Passes"), "パス");
        assert_eq!(Lang::Ja.tr("|difference|"), "|差|");
        // Every id is listed once.
        for (i, (en, _)) in JA.iter().enumerate() {
            assert!(!JA[..i].iter().any(|(e, _)| e == en), "{en} twice");
        }
    }
}
