//! The course's terms in English and in the lectures' Japanese: one table, which the
//! built-in Japanese labels follow, `docs/glossary.md` lists and the site prints as
//! `glossary.html`.

/// One term of the course.
#[derive(Debug, Clone, Copy)]
pub struct Term {
    /// The topic the term belongs to (a heading of the glossary).
    pub topic: &'static str,
    /// The English term, as lessons and the CLI write it.
    pub en: &'static str,
    /// The term as the Japanese lectures write it.
    pub ja: &'static str,
    /// The course's symbol or a short note (may be empty).
    pub note: &'static str,
}

const fn t(topic: &'static str, en: &'static str, ja: &'static str, note: &'static str) -> Term {
    Term { topic, en, ja, note }
}

/// Classic shading.
const CLASSIC: &str = "Classic shading";
/// Physically based shading.
const PBR: &str = "Physically based shading";
/// Radiometry.
const RADIOMETRY: &str = "Radiometry";
/// Lights and shadows.
const LIGHTS: &str = "Lights and shadows";
/// Environment, reflection and refraction.
const ENVIRONMENT: &str = "Environment, reflection and refraction";
/// Fog and global illumination.
const TRANSPORT: &str = "Fog and global illumination";
/// Sampling and cost.
const SAMPLING: &str = "Sampling and cost";

/// Every term, grouped by topic in the order of the course.
pub const GLOSSARY: &[Term] = &[
    t(CLASSIC, "illumination equation", "照明方程式", "I = L_glob⊗K_amb + L_emi + Σ d (I_diff + I_spec)"),
    t(CLASSIC, "ambient term", "環境光反射成分", "L_glob⊗K_amb"),
    t(CLASSIC, "diffuse term", "拡散反射成分", "max(N·L, 0) K_diff⊗L_diff"),
    t(CLASSIC, "specular term", "鏡面反射成分", "max(R·V, 0)^K_shi K_spec⊗L_spec"),
    t(CLASSIC, "ambient light", "環境光", "L_glob, L_amb"),
    t(CLASSIC, "diffuse reflection", "拡散反射", ""),
    t(CLASSIC, "specular reflection", "鏡面反射", ""),
    t(CLASSIC, "shininess", "光沢度", "K_shi"),
    t(CLASSIC, "highlight", "ハイライト", ""),
    t(CLASSIC, "normal", "法線", "N"),
    t(CLASSIC, "vertex normal", "頂点法線", ""),
    t(CLASSIC, "terminator", "明暗境界線", "N·L = 0"),
    t(CLASSIC, "flat shading", "フラットシェーディング", ""),
    t(CLASSIC, "Gouraud shading", "グローシェーディング", "the lectures spell Gouraud グロー; labels read グロー (Gouraud)"),
    t(CLASSIC, "Phong shading", "フォンシェーディング", "normals interpolated"),
    t(CLASSIC, "Blinn-Phong", "ブリン・フォン", "N·H"),
    t(CLASSIC, "Lambert", "ランバート", "cosine law"),
    t(CLASSIC, "interpolation", "補間", ""),
    t(CLASSIC, "barycentric coordinates", "重心座標", ""),
    t(CLASSIC, "perspective-correct", "透視補正", ""),
    t(CLASSIC, "emission", "自己発光", "L_emi; 放射 is only the radiometric prefix"),
    t(PBR, "BRDF", "双方向反射率分布関数 (BRDF)", "f_r = dL_o / dE_i"),
    t(PBR, "BTDF", "双方向透過率分布関数 (BTDF)", ""),
    t(PBR, "BSDF", "双方向散乱分布関数 (BSDF)", "BRDF + BTDF"),
    t(PBR, "microfacet", "微小面", ""),
    t(PBR, "normal distribution function", "法線分布関数 (NDF)", "D"),
    t(PBR, "masking-shadowing", "マスキング・シャドウイング関数", "G"),
    t(PBR, "Fresnel", "フレネル", "F"),
    t(PBR, "index of refraction", "屈折率", "η"),
    t(PBR, "roughness", "粗さ", "r, α = r²"),
    t(PBR, "metal", "金属", ""),
    t(PBR, "dielectric", "誘電体", ""),
    t(PBR, "albedo", "アルベド", "ρ"),
    t(PBR, "energy conservation", "エネルギー保存", ""),
    t(PBR, "reciprocity", "相反性", "f(l, v) = f(v, l)"),
    t(PBR, "Oren-Nayar", "オーレン・ネイヤー", "σ"),
    t(PBR, "Disney principled BRDF", "ディズニーのプリンシプルド BRDF", ""),
    t(PBR, "transmission", "透過", ""),
    t(PBR, "specular transmission", "鏡面透過", "specular_transmission"),
    t(PBR, "diffuse transmission", "拡散透過", "d_t C/π"),
    t(PBR, "transmittance", "透過率", "T = exp(−σ_a d)"),
    t(RADIOMETRY, "radiance", "放射輝度", "L, W m⁻² sr⁻¹"),
    t(RADIOMETRY, "irradiance", "放射照度", "E, W m⁻²"),
    t(RADIOMETRY, "radiant flux", "放射束", "Φ, W"),
    t(RADIOMETRY, "radiant intensity", "放射強度", "I, W sr⁻¹"),
    t(RADIOMETRY, "solid angle", "立体角", "ω, sr"),
    t(RADIOMETRY, "steradian", "ステラジアン", "sr"),
    t(LIGHTS, "light source", "光源", ""),
    t(LIGHTS, "directional light", "平行光源", ""),
    t(LIGHTS, "point light", "点光源", ""),
    t(LIGHTS, "spot light", "スポットライト", "C_spot"),
    t(LIGHTS, "attenuation", "減衰", "1/(S_c + S_l d + S_q d²)"),
    t(LIGHTS, "area light", "面光源", ""),
    t(LIGHTS, "line light", "線光源", ""),
    t(LIGHTS, "sky light", "天空光", ""),
    t(LIGHTS, "three-point lighting", "三点照明", "key, fill, back"),
    t(LIGHTS, "key light", "キーライト", ""),
    t(LIGHTS, "fill light", "フィルライト", ""),
    t(LIGHTS, "back light", "バックライト (リムライト)", ""),
    t(LIGHTS, "shadow", "影", ""),
    t(LIGHTS, "umbra", "本影", ""),
    t(LIGHTS, "penumbra", "半影", ""),
    t(LIGHTS, "shadow ray", "シャドウレイ", ""),
    t(LIGHTS, "shadow map", "シャドウマップ", ""),
    t(LIGHTS, "shadow acne", "シャドウアクネ", ""),
    t(LIGHTS, "soft shadow", "ソフトシャドウ", ""),
    t(LIGHTS, "hard shadow", "ハードシャドウ", ""),
    t(LIGHTS, "shadow volume", "シャドウボリューム", "Crow 1977"),
    t(LIGHTS, "silhouette edge", "シルエットエッジ", "shared by a lit and an unlit face"),
    t(LIGHTS, "stencil count", "ステンシル値", "z-pass: +1 entering, −1 leaving"),
    t(LIGHTS, "shadow polygon", "影ポリゴン", "Atherton, Weiler & Greenberg 1978"),
    t(LIGHTS, "occluder", "遮蔽物", ""),
    t(LIGHTS, "receiver", "受け手", "the surface a shadow falls on"),
    t(ENVIRONMENT, "environment map", "環境マップ", ""),
    t(ENVIRONMENT, "cube map", "キューブマップ", ""),
    t(ENVIRONMENT, "image-based lighting", "イメージベースドライティング (IBL)", ""),
    t(ENVIRONMENT, "split sum", "スプリットサム近似", ""),
    t(ENVIRONMENT, "spherical harmonics", "球面調和関数 (SH)", ""),
    t(ENVIRONMENT, "reflection probe", "反射プローブ", ""),
    t(ENVIRONMENT, "box projection", "ボックス投影", ""),
    t(ENVIRONMENT, "moved probe", "移動したプローブ", "s′ = x − C + [((B − x)·n)/((C′ − x)·n)](C′ − x)"),
    t(ENVIRONMENT, "probe as a light projector", "光のプロジェクタとしてのプローブ", "s = x − c"),
    t(ENVIRONMENT, "refraction", "屈折", "Snell: n₁ sin θ₁ = n₂ sin θ₂"),
    t(ENVIRONMENT, "total internal reflection", "全反射", "θ > θ_c = arcsin(n₂/n₁)"),
    t(TRANSPORT, "fog", "フォグ (霧)", ""),
    t(TRANSPORT, "scattering", "散乱", "σ_s"),
    t(TRANSPORT, "absorption", "吸収", "σ_a"),
    t(TRANSPORT, "extinction", "消散", "σ_t = σ_a + σ_s"),
    t(TRANSPORT, "ray marching", "レイマーチング", ""),
    t(TRANSPORT, "single scattering", "単一散乱", ""),
    t(TRANSPORT, "single-scattering albedo", "単一散乱アルベド", "ω = σ_s / σ_t"),
    t(TRANSPORT, "random walk", "ランダムウォーク", ""),
    t(TRANSPORT, "optical thickness", "光学的厚さ", "τ = σ_t d"),
    t(TRANSPORT, "phase function", "位相関数", "p(θ), Henyey-Greenstein g"),
    t(TRANSPORT, "radiosity", "ラジオシティ", "L = E + ρFL"),
    t(TRANSPORT, "form factor", "形態係数", "F_ij"),
    t(TRANSPORT, "patch", "パッチ", ""),
    t(TRANSPORT, "hemicube", "ヘミキューブ", ""),
    t(TRANSPORT, "progressive refinement", "漸進的ラジオシティ", ""),
    t(TRANSPORT, "colour bleeding", "カラーブリーディング", ""),
    t(TRANSPORT, "global illumination", "大域照明", ""),
    t(TRANSPORT, "caustic", "コースティクス", "light focused by mirrors or glass onto a surface"),
    t(TRANSPORT, "photon mapping", "フォトンマッピング", "Jensen 1996: L ≈ Σ f ΔΦ / (π r²)"),
    t(
        TRANSPORT,
        "global photon map",
        "大域フォトンマップ",
        "photons stored at every diffuse surface they meet: all the light, read for indirect light",
    ),
    t(
        TRANSPORT,
        "final gather",
        "ファイナルギャザー",
        "rays from a surface point that read the global photon map where they land (Jensen 1996)",
    ),
    t(TRANSPORT, "local illumination", "局所照明", "light straight from the lamps only"),
    t(TRANSPORT, "subsurface scattering", "表面下散乱", "サブサーフェス・スキャタリング: light leaves away from where it entered"),
    t(TRANSPORT, "BSSRDF", "BSSRDF", "S(x_i, ω_i; x_o, ω_o)"),
    t(TRANSPORT, "scatter distance", "散乱距離", "subsurface_radius × subsurface_scale"),
    t(TRANSPORT, "mean free path", "平均自由行程", "ℓ = 1/σ_t"),
    t(TRANSPORT, "diffusion dipole", "拡散ダイポール", "Jensen et al. 2001: R_d(r)"),
    t(SAMPLING, "texture", "テクスチャ", ""),
    t(SAMPLING, "normal map", "法線マップ", ""),
    t(SAMPLING, "mipmap", "ミップマップ", ""),
    t(SAMPLING, "sampling", "サンプリング", ""),
    t(SAMPLING, "stratified sampling", "層化サンプリング", ""),
    t(SAMPLING, "noise", "ノイズ", ""),
    t(SAMPLING, "reference", "参照解", "what each approximation is measured against"),
    t(SAMPLING, "error", "誤差", "RMSE, PSNR"),
    t(SAMPLING, "pixel", "画素", ""),
];

/// The topics in the order of the course.
pub fn topics() -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for term in GLOSSARY {
        if !out.contains(&term.topic) {
            out.push(term.topic);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::i18n::Lang;

    #[test]
    fn every_term_is_listed_once_and_the_built_in_labels_follow_the_glossary() {
        for (i, term) in GLOSSARY.iter().enumerate() {
            assert!(!GLOSSARY[..i].iter().any(|o| o.en == term.en), "{} twice", term.en);
            assert!(!term.ja.is_empty() && !term.en.is_empty());
        }
        assert_eq!(topics().len(), 7);
        // Where a built-in label is a glossary term, it is translated as the glossary says.
        let mut checked = 0;
        for term in GLOSSARY {
            let ja = Lang::Ja.tr(term.en);
            if ja != term.en {
                assert!(term.ja.starts_with(ja) || ja.starts_with(term.ja), "{}: label {ja}, glossary {}", term.en, term.ja);
                checked += 1;
            }
        }
        assert!(checked >= 8, "{checked} terms are built-in labels too");
        // The lectures' spellings, which the issue names.
        let ja = |en: &str| GLOSSARY.iter().find(|t| t.en == en).unwrap().ja;
        assert_eq!(ja("emission"), "自己発光");
        assert_eq!(ja("area light"), "面光源");
        assert_eq!(ja("transmission"), "透過");
        assert_eq!((ja("umbra"), ja("penumbra")), ("本影", "半影"));
        assert!(ja("Gouraud shading").starts_with("グロー"));
        assert_eq!(Lang::Ja.tr("Gouraud"), "グロー (Gouraud)");
    }
}
