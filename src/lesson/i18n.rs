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
            Lang::Ja => JA.iter().chain(JA_EXPLAIN).find(|(en, _)| *en == text).map_or(text, |(_, ja)| ja),
        }
    }

    /// `text` (a built-in English message, perhaps with values in it) in this language: a
    /// label of the table as [`Lang::tr`], else the first message template (English with
    /// `{}` holes) that the whole text fits, its holes put back into the translation's `{0}`,
    /// `{1}`, ... each translated in turn (a hole may be a phrase of the table). Text that
    /// fits nothing is returned as it is, so a user's own words pass through.
    pub fn say(self, text: &str) -> String {
        if self == Lang::En {
            return text.to_string();
        }
        let exact = self.tr(text);
        if exact != text {
            return exact.to_string();
        }
        for (template, ja) in TEMPLATES {
            let parts: Vec<&str> = template.split("{}").collect();
            let Some(rest) = text.strip_prefix(parts[0]) else { continue };
            let mut holes = Vec::new();
            if fit(&parts[1..], rest, &mut holes) {
                let mut out = ja.to_string();
                for (i, hole) in holes.iter().enumerate() {
                    out = out.replace(&format!("{{{i}}}"), &self.say(hole));
                }
                return out;
            }
        }
        text.to_string()
    }
}

/// Whether `rest` is a hole followed by `parts[0]`, a hole, `parts[1]`, ... (the literal
/// pieces after each hole of a template), shortest holes first; pushes the holes.
fn fit<'a>(parts: &[&str], rest: &'a str, holes: &mut Vec<&'a str>) -> bool {
    let Some((&literal, later)) = parts.split_first() else { return rest.is_empty() };
    if later.is_empty() {
        return match rest.strip_suffix(literal) {
            Some(hole) => {
                holes.push(hole);
                true
            }
            None => false,
        };
    }
    for (i, _) in rest.match_indices(literal) {
        holes.push(&rest[..i]);
        if fit(later, &rest[i + literal.len()..], holes) {
            return true;
        }
        holes.pop();
    }
    false
}

/// English → Japanese, in the course's terms (環境光反射成分, 拡散反射成分, 鏡面反射成分).
use super::i18n_explain::JA_EXPLAIN;

const JA: &[(&str, &str)] = &[
    // `explain`: the path tracer's pass with `indirect = "none"` (a part after "; ").
    (
        "no indirect light: paths end at the first diffuse vertex (local illumination)",
        "間接光なし：パスは最初の拡散面の頂点で終わる (局所照明)",
    ),
    // Cost figures: the ladders, their rungs and series (the ladders' keys name them in
    // lesson files; figures show the words).
    ("interpolation", "補間"),
    ("tessellation", "分割数"),
    ("aa", "アンチエイリアス"),
    ("fresnel", "フレネル"),
    ("shadow_map", "シャドウマップの解像度"),
    ("pcf", "PCF の幅"),
    ("area_samples", "面光源のサンプル数"),
    ("sampler", "サンプラー"),
    ("shadow_bias", "シャドウバイアス"),
    ("interpolation_space", "補間の空間"),
    ("normal_transform", "法線の変換"),
    ("fog_steps", "霧のステップ数"),
    ("ibl", "IBL の方式"),
    ("env_samples", "環境光のサンプル数"),
    ("prefilter_size", "プリフィルタの解像度"),
    ("hemicube", "ヘミキューブの解像度"),
    ("iterations", "反復回数"),
    ("probe", "プローブの解像度"),
    ("texture_filter", "テクスチャフィルタ"),
    ("max_bounces", "最大反射回数"),
    ("spp", "1 画素あたりのパス数"),
    ("max_depth", "パスの最大の長さ"),
    ("shadow_methods", "影の生成法と分割数"),
    ("ray", "シャドウレイ"),
    ("map", "シャドウマップ"),
    ("volume", "シャドウボリューム"),
    ("polygons", "影ポリゴン"),
    ("flat", "フラット"),
    ("exact", "厳密"),
    ("Schlick", "シュリック"),
    ("sh", "SH"),
    ("prefiltered", "プリフィルタ済み"),
    ("nearest", "最近傍"),
    ("bilinear", "バイリニア"),
    ("trilinear", "トライリニア"),
    ("screen", "スクリーン空間"),
    ("perspective", "透視補正"),
    ("naive", "単純"),
    ("inverse_transpose", "逆転置"),
    ("independent", "独立"),
    ("stratified", "層化"),
    ("sobol", "Sobol"),
    ("uniform", "等間隔"),
    ("equiangular", "等角"),
    ("box", "ボックス投影"),
    ("by area", "面積で"),
    ("by solid angle", "立体角で"),
    ("the traced reflection", "レイトレースした映り込み"),
    ("the exact rect-light irradiance", "矩形光源の厳密な放射照度"),
    ("ray-cast shadows", "レイキャストの影"),
    ("|error|, linear radiance", "|誤差|, 線形放射輝度"),
    ("measured profile", "測定した配光"),
    ("Transmission", "透過"),
    ("each point its own pattern", "点ごとに別のパターン"),
    ("one pattern for every point (steps, not grain)", "全点で共通のパターン (ノイズではなく段差)"),
    ("total", "合計"),
    (
        "PSNR < 0 dB: the RMSE is above linear white, the PSNR's peak (an HDR reference).",
        "PSNR < 0 dB: RMSE が線形の白 (PSNR のピーク) を超えている (HDR の参照解)。",
    ),
    // Split layers.
    ("Ambient", "環境光"),
    ("Diffuse", "拡散反射"),
    ("Specular", "鏡面反射"),
    ("Emission", "自己発光"),
    ("Reflection", "映り込み"),
    ("Total", "合計"),
    ("Normal", "法線"),
    // Interpolation, models, light kinds as column labels.
    ("Flat", "フラット"),
    ("Gouraud", "グロー (Gouraud)"),
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
    // Figures: default titles and row labels.
    ("BRDF lobe: f·cos θₒ in the plane of incidence", "BRDF のローブ: 入射面内の f·cos θₒ"),
    ("Spot distribution: C_spot(θ) from the spot's axis", "スポットライトの配光: 軸からの角 θ の C_spot(θ)"),
    ("Directional albedo (white furnace)", "方向アルベド (ホワイトファーネス)"),
    ("What accuracy costs", "精度と計算時間"),
    ("ladder", "段階"),
    ("render", "描画"),
    ("error", "誤差"),
    ("|difference|", "|差|"),
    ("the reference", "参照解"),
    // `cost` table headers.
    ("rung", "段"),
    ("triangles", "三角形"),
    ("median ms", "中央値 ms"),
    ("min ms", "最小 ms"),
    ("max ms", "最大 ms"),
    ("max err", "最大誤差"),
    ("visible %", "可視 %"),
    ("front", "パレート"),
    ("reference", "参照解"),
    // Charts: axis titles, legends and notes.
    ("f·cos θₒ (BRDFs), I (classic)  (towards the mirror side →)", "f·cos θₒ (BRDF), I (古典モデル)  (正反射の側へ →)"),
    ("I, the course's equation for a unit light  (towards the mirror side →)", "I, 単位光源での講義の式  (正反射の側へ →)"),
    ("f·cos θₒ  (towards the mirror side →)", "f·cos θₒ  (正反射の側へ →)"),
    ("angle of incidence θᵢ (degrees)", "入射角 θᵢ (度)"),
    ("albedo", "アルベド"),
    ("median render time (ms, log scale)", "描画時間の中央値 (ms, 対数目盛)"),
    ("RMSE (log scale)", "RMSE (対数目盛)"),
    ("Pareto front: nothing is both faster and more accurate", "パレートフロント: これより速く, しかも正確なものはない"),
    ("iteration", "反復"),
    ("relative residual (log scale)", "相対残差 (対数目盛)"),
    ("Radiosity solvers: residual against iteration", "ラジオシティの解法: 反復ごとの残差"),
    ("along the normal", "法線の方向"),
    ("grey: the surface, the normal, and the direction towards the light", "灰色: 表面, 法線, 光源への方向"),
    ("along the spot's axis", "スポットライトの軸の方向"),
    ("grey: the spot's axis; θ is measured from it", "灰色: スポットライトの軸 (θ はここから測る)"),
    ("the exact ray cast", "厳密なレイキャスト"),
    ("the finest rung", "最も細かい段"),
    // `explain --pixel` and the `probe` figure.
    ("pixel", "画素"),
    ("normal", "法線"),
    ("toward the eye", "視点の方向"),
    ("toward the light", "光源の方向"),
    ("mirror direction of L", "L の正反射方向"),
    ("half vector", "ハーフベクトル"),
    ("terms as relative luminance Y (linear)", "各項の相対輝度 Y (リニア)"),
    ("light", "光源"),
    ("global ambient", "大域環境光"),
    ("reflection", "反射"),
    ("transmission", "透過"),
    ("background", "背景"),
    ("One pixel, explained", "1 画素の解説"),
    ("radiosity B", "ラジオシティ B"),
    ("face normal", "面法線"),
    ("triangle", "三角形"),
    ("farther: in shadow", "より遠い: 影"),
    ("not farther: lit", "遠くない: 照らされる"),
    ("shadow map, nearest surface the light sees at the point's texel", "シャドウマップ: 点のテクセルで光源から見える最も近い面"),
    ("the point", "この点"),
    ("after the bias", "バイアス後"),
    ("weight", "重み"),
    ("visibility", "可視度"),
    ("no shadows", "影なし"),
    ("blocked by object", "遮る物体"),
    ("unblocked", "遮られない"),
    ("blocked", "遮られる"),
    ("partly blocked", "一部が遮られる"),
    ("exposure in stops", "露出 (段)"),
    ("tone map", "トーンマップ"),
    ("sum of the terms", "項の和"),
    ("rendered sample (linear)", "描画されたサンプル (リニア)"),
    ("rendered − sum", "描画値 − 和"),
    ("rendered (linear)", "描画値 (リニア)"),
    ("reflection (environment, mirrors)", "反射 (環境・鏡)"),
    ("transmission (glass)", "透過 (ガラス)"),
    ("radiosity of the patch (all lights, all bounces)", "パッチのラジオシティ (全光源・全バウンス)"),
    ("fog (in-scattered light − what the fog absorbed)", "霧 (散乱で加わる光 − 霧が吸収した光)"),
    ("lit at this sample (Phong interpolation)", "このサンプルで照明計算 (フォン補間)"),
    ("lit at the triangle's vertices, their values interpolated (Gouraud)", "三角形の頂点で照明計算し, 値を補間 (グロー)"),
    ("lit once per face at its centroid (flat)", "面の重心で 1 回だけ照明計算 (フラット)"),
    ("lit by the radiosity solution", "ラジオシティの解で照明"),
    ("the background: no surface is seen here, nothing is shaded", "背景: ここに面はなく, シェーディングされない"),
    ("Gouraud: the vertices' lit values, weighted by the sample's barycentrics", "グロー: 頂点の照明値をサンプルの重心座標で重み付け"),
    ("incidents (means below)", "入射 (以下は平均)"),
    ("a delta BRDF: no light reaches the eye from this light directly", "デルタ BRDF: この光源の光は直接は目に届かない"),
    ("(vectors at the sample; the terms are the vertices' values, interpolated)", "(ベクトルはサンプル位置のもの; 項は頂点の値の補間)"),
    // `walk` figures: a random walk in a slab.
    ("A random walk in a slab: why diffuse light is coloured", "スラブ内のランダムウォーク: 拡散反射光に色がつくわけ"),
    ("Where the light leaves: radiance against the exit angle", "光はどの向きに出るか: 出射角に対する放射輝度"),
    ("exit angle θ from the normal (degrees)", "法線からの出射角 θ (度)"),
    ("radiance relative to Lambert", "ランベルト反射に対する放射輝度の比"),
    ("1 scattering", "1 回の散乱"),
    ("all reflected light", "反射光の全体"),
    ("Lambert: the same in every direction", "ランベルト: どの向きにも同じ"),
    ("Which light leaves: the absorption colours the long walks", "どの光が出るか: 長い経路ほど吸収で色がつく"),
    ("scatterings before leaving, n (log scale)", "出るまでの散乱回数 n (対数目盛)"),
    // `bssrdf` figures: the radial exit profile.
    ("Where light leaves: the radial exit profile R(r)", "光はどこから出るか: 動径方向の出射プロファイル R(r)"),
    ("distance r from the entry point (world units, log scale)", "入射点からの距離 r (ワールド単位, 対数目盛)"),
    ("2π r² R(r): light leaving per unit of ln r", "2π r² R(r): ln r あたりの出射光"),
    ("random walk (the path tracer's), histogram", "ランダムウォーク (パストレーサと同じもの) のヒストグラム"),
    ("Burley 2015 normalized diffusion (dashed)", "Burley 2015 の正規化拡散 (破線)"),
    ("dipole, Jensen et al. 2001 (dotted)", "ダイポール近似, Jensen ら 2001 (点線)"),
    ("energy reflected within n scatterings", "散乱 n 回以内で反射したエネルギー"),
    ("the reflected colour (white light in)", "反射光の色 (白色光を入射)"),
    ("A rough dielectric: the BSDF as BRDF plus BTDF (Walter et al. 2007)", "粗い誘電体: BSDF = BRDF + BTDF (ウォルターら 2007)"),
    ("BSDF = BRDF (above) + BTDF (below): f·|cos θₒ|", "BSDF = BRDF (面の上) + BTDF (面の下): f·|cos θₒ|"),
    ("outside (air)", "外側 (空気)"),
    ("inside (glass)", "内側 (ガラス)"),
    ("Where a beam's energy goes", "入射光のエネルギーの行き先"),
    ("share of the incident energy", "入射エネルギーに対する割合"),
    ("smooth glass: 1 − F and F", "滑らかなガラス: 1 − F と F"),
    (
        "solid: transmitted T; dashed: reflected R; 1 − R − T: light that would meet a second microfacet",
        "実線: 透過 T; 破線: 反射 R; 1 − R − T: 2 つ目の微小面に当たるはずの光",
    ),
    ("red", "赤"),
    ("green", "緑"),
    ("blue", "青"),
];

/// Messages with values in them: English templates, each `{}` a hole that matches any text,
/// and their Japanese with the holes as `{0}`, `{1}`, ... (a hole it does not name, such as
/// a plural "s", is dropped). Read by [`Lang::say`], first fit first.
const TEMPLATES: &[(&str, &str)] = &[
    // `explain`: the path tracer's pass, with photon maps (each part after "; ", translated by the templates below).
    (
        "random-walk subsurface scattering for {} of the materials, at most {} steps a walk",
        "{0} 個の材質で表面下散乱をランダムウォークで追跡 (1 回のウォークは最大 {1} ステップ)",
    ),
    (
        "random walk under the surface for a share {} of the diffuse lobe: mean free path ({}, {}, {}), isotropic, at most {} steps",
        "拡散反射ローブのうち {0} の割合で表面下をランダムウォーク：平均自由行程 ({1}, {2}, {3})、等方散乱、最大 {4} ステップ",
    ),
    (
        "{} paths a pixel ({}² samples × spp {}), up to {} segments each, next-event estimation with MIS; {}",
        "1 画素あたり {0} 本のパス ({1}² サンプル × spp {2})、各パスは最大 {3} 線分、MIS 付きのネクストイベント推定。{4}",
    ),
    // `explain`: the path tracer's pass.
    (
        "{} paths a pixel ({}² samples × spp {}), up to {} segments each, next-event estimation with MIS",
        "1 画素あたり {0} 本のパス ({1}² サンプル × spp {2})、各パスは最大 {3} 線分、MIS 付きのネクストイベント推定",
    ),
    // `explain`: the photon passes' parts (joined by "; ", last in this table).
    (
        "caustics from a photon map gathered {}: {} photons from the rect, disk, sphere, point and spot lights through mirrors and glass",
        "コースティクスはフォトンマップから{0}集める：矩形・円板・球・点・スポットの光源から {1} 個のフォトンを放ち、鏡とガラスを通す",
    ),
    (
        "indirect light by a final gather: the global photon map of {} photons, gathered {}, read where {} rays from the first diffuse vertex land",
        "間接光はファイナルギャザーで：最初の拡散面の頂点から {2} 本の光線を放ち、当たった所で {0} 個のフォトンの大域フォトンマップを{1}読む",
    ),
    (
        "indirect light read from the global photon map of {} photons at the first diffuse vertex, {} (no final gather)",
        "間接光は最初の拡散面の頂点で {0} 個のフォトンの大域フォトンマップから直接、{1}読む (ファイナルギャザーなし)",
    ),
    ("within r = {}", "半径 r = {0} 以内で"),
    ("from the {} nearest within r = {}", "半径 r = {1} 以内の最も近い {0} 個から"),
    // `explain`: a sampled light's samples and whose they are.
    ("reaches the scene; {} samples a point, {}", "シーンに届く; 1 点あたり {0} サンプル, {1}"),
    // Generated labels: a varied key and its value (keys with `_` as label markup escapes them).
    ("roughness = {}", "粗さ = {0}"),
    ("metallic = {}", "メタリック = {0}"),
    ("sheen = {}", "シーン = {0}"),
    ("sheen\\_tint = {}", "シーンの色合い = {0}"),
    ("clearcoat = {}", "クリアコート = {0}"),
    ("clearcoat\\_gloss = {}", "クリアコートの光沢 = {0}"),
    ("anisotropic = {}", "異方性 = {0}"),
    ("subsurface = {}", "サブサーフェス = {0}"),
    ("specular\\_tint = {}", "スペキュラーの色合い = {0}"),
    ("segments = {}", "分割数 = {0}"),
    ("rings = {}", "リング数 = {0}"),
    ("subdivisions = {}", "細分割 = {0}"),
    ("ior = {}", "屈折率 = {0}"),
    ("exposure = {}", "露出 = {0}"),
    ("samples = {}", "サンプル数 = {0}"),
    ("size = {}", "大きさ = {0}"),
    ("direction = {}", "方向 = {0}"),
    ("position = {}", "位置 = {0}"),
    ("cutoff = {}°", "カットオフ = {0}°"),
    ("fov = {}°", "視野角 = {0}°"),
    ("rotate = {}°", "回転 = {0}°"),
    ("density = {}", "密度 = {0}"),
    ("steps = {}", "ステップ数 = {0}"),
    // `explain`: what each decision is about.
    ("light {} ({})", "光源 {0} ({1})"),
    // `explain`: reasons with values.
    ("culled: its {}° cone misses every object", "カリング: {0}° の円錐がどの物体にも届かない"),
    ("{} vertices to clip space", "頂点 {0} 個をクリップ空間へ"),
    ("BVH over {} triangles; any-hit shadow rays for {} light{}", "三角形 {0} 個の BVH; 光源 {1} 個への any-hit シャドウレイ"),
    (
        "silhouettes of {} triangles seen from {} light{} extruded away from it; each sample counts the volume faces in front of it (z-pass)",
        "三角形 {0} 個のシルエットを光源 {1} 個から見て押し出す; 各サンプルで手前にあるボリュームの面を数える (z-pass)",
    ),
    (
        "{} receivers × {} occluders projected from {} light{} (n² pairs); each sample tests its receiver's polygons",
        "受け手 {0} 個 × 遮蔽物 {1} 個を光源 {2} 個から投影 (n² 組); 各サンプルは自分の受け手の影ポリゴンを調べる",
    ),
    ("{} points × ≈ {} quads × {} lights", "点 {0} 個 × 約 {1} 個の四角形 × 光源 {2} 個"),
    ("{} receivers × {} occluders × {} lights", "受け手 {0} 個 × 遮蔽物 {1} 個 × 光源 {2} 個"),
    (
        "depth from {} light{} at {} texels a face (bias {}, slope {}, normal offset {} texels, PCF {})",
        "光源 {0} 個からの深度, 1 面 {2} テクセル (bias {3}, slope {4}, normal_offset {5} テクセル, PCF {6})",
    ),
    ("{}; BVH for environment visibility and mirror rays", "{0}; 環境の可視判定と鏡のレイに BVH"),
    (
        "{} map: luminance sampling tables; Monte Carlo (ibl = \"reference\"), {} samples per point (MIS with the BRDF)",
        "{0} のマップ: 輝度によるサンプリング表; モンテカルロ (ibl = \"reference\"), 1 点 {1} サンプル (BRDF との MIS)",
    ),
    (
        "prefilter of the {} map ({}): {} GGX levels from {}, irradiance {} (ibl = \"{}\"); specular albedo tables",
        "{0} のマップの事前フィルタ ({1}): {3} から GGX {2} 段, 放射照度 {4} (ibl = \"{5}\"); 鏡面反射アルベドの表",
    ),
    ("cache hit, computed in {} ms", "キャッシュあり ({0} ms で計算済み)"),
    (
        "{} probe{}: 6 faces of {} texels each, the scene without its mirrors; lookup {}",
        "プローブ {0} 個: {2} テクセルの面 6 枚, 鏡を除いたシーン; 参照 {3}",
    ),
    (
        "glass {}: Fresnel-weighted reflected and refracted rays through the scene's BVH, up to {} bounce{} a path (max_bounces)",
        "ガラス {0}: フレネルで重みづけた反射・屈折レイをシーンの BVH で追跡, 1 経路 {1} 回まで (max_bounces)",
    ),
    (
        "{} patches (patch_size {}), form factors by {}, {} (≤ {} iterations, tolerance {}){}",
        "パッチ {0} 個 (patch_size {1}), 形態係数は{2}, {3} (反復 ≤ {4} 回, 許容誤差 {5}){6}",
    ),
    ("hemicube {}", "ヘミキューブ {0}"),
    ("Gouraud: {} vertices × {} light{}, colours interpolated", "グロー: 頂点 {0} 個 × 光源 {1} 個, 色を補間"),
    ("flat: {} faces × {} light{}, once each at the centroid", "フラット: 面 {0} 個 × 光源 {1} 個, 各面の重心で 1 回"),
    ("{} triangles on {} samples (aa {}: {} per pixel)", "三角形 {0} 個, {1} サンプル (aa {2}: 1 画素 {3})"),
    ("Phong: normals interpolated, {} light{} at every visible sample", "フォン: 法線を補間, 可視サンプルごとに光源 {0} 個"),
    (
        "linear fog f = (end − z)/(end − start), start {}, end {}, {}; {} samples",
        "線形フォグ f = (end − z)/(end − start), start {0}, end {1}, {2}; {3} サンプル",
    ),
    ("exp fog f = e^(−{}·z), {}; {} samples", "指数フォグ f = e^(−{0}·z), {1}; {2} サンプル"),
    ("exp2 fog f = e^(−({}·z)²), {}; {} samples", "指数二乗フォグ f = e^(−({0}·z)²), {1}; {2} サンプル"),
    (
        "medium σ_s {}, σ_a {}, g {}: {} steps per sample × {} samples, {} light{} scattering",
        "媒質 σ_s {0}, σ_a {1}, g {2}: 1 サンプル {3} ステップ × {4} サンプル, 散乱する光源 {5} 個",
    ),
    ("box filter of {} samples per pixel", "1 画素 {0} サンプルのボックスフィルタ"),
    (
        "residual Σ A|E + ρFL − L| / Σ A L, per iteration (tolerance {}, at most {} iterations):",
        "残差 Σ A|E + ρFL − L| / Σ A L, 反復ごと (許容誤差 {0}, 最大 {1} 回):",
    ),
    ("≈ {} of work on one core, {}", "1 コアで約 {0} の処理, {1}"),
    ("Probe capture ({} probe{}, six faces each): {} ms", "プローブの取り込み (プローブ {0} 個, 各 6 面): {2} ms"),
    // Charts.
    (
        "largest channel; integration error bound ≤ {} (Gauss-Legendre, {} vs {} nodes per panel)",
        "最大のチャンネル; 積分誤差の上界 ≤ {0} (ガウス・ルジャンドル, 区間あたり {1} 対 {2} 節点)",
    ),
    ("{} (error 0)", "{0} (誤差 0)"),
    ("tolerance {}", "許容誤差 {0}"),
    ("{}: error against time", "{0}: 誤差と計算時間"),
    ("{}: the {} ladder, error against time", "{0}: {1} の段階, 誤差と計算時間"),
    ("{}: {} iterations", "{0}: {1} 回"),
    ("{} iterations", "{0} 回"),
    (
        "{} patches, {} non-zero form factors; residual Σ A|E + ρFL − L| / Σ A L after each iteration (0: L = E)",
        "パッチ {0} 個, 非 0 の形態係数 {1} 個; 各反復後の残差 Σ A|E + ρFL − L| / Σ A L (0: L = E)",
    ),
    (
        "median of {} runs, {} threads; error: RMSE in linear radiance against {}; filled: on the front",
        "{0} 回の中央値, {1} スレッド; 誤差: {2} に対する線形放射輝度の RMSE; 塗りつぶし: フロント上",
    ),
    // `explain --pixel` and the `probe` figure's captions.
    (
        "aa = {}: this explains the pixel's centre sample, rendered alone at aa = 1",
        "aa = {0}: 画素中心のサンプル (aa = 1 で単独に描画) を説明する",
    ),
    ("rendered pixel, mean of {} samples", "描画された画素 ({0} サンプルの平均)"),
    ("{}: the background; nothing is shaded there.", "{0}: 背景; シェーディングされない."),
    ("{}: Y = {} at \"{}\"", "{0}: \"{2}\" で Y = {1}"),
    ("the largest term is {} ({}%)", "最大の項は {0} ({1}%)"),
    ("light {} diffuse", "光源 {0} の拡散反射"),
    ("light {} specular", "光源 {0} の鏡面反射"),
    ("with N·L = {}", "N·L = {0}"),
    ("light {} visibility {}", "光源 {0} の可視度 {1}"),
    ("shadowed: {}", "影: {0}"),
    ("Gouraud: the vertices' values (Y {}) weighted {}", "グロー: 頂点の値 (Y {0}) を重み {1} で補間"),
    // `bsdf` figures: the lobe chart's note, its magnification and the legend entries.
    (
        "θᵢ = {}°, η = {}; each roughness scaled to its peak; smooth glass (dashed): F = {}, 1 − F = {}",
        "θᵢ = {0}°, η = {1}; 粗さごとに最大値で正規化; 滑らかなガラス (破線): F = {2}, 1 − F = {3}",
    ),
    ("above the surface: × {}", "面の上は × {0}"),
    ("roughness {}: R = {}, T = {}", "粗さ {0}: R = {1}, T = {2}"),
    // `walk` figures: the notes under the charts and the legend entries.
    (
        "{} walks in at θ₀ = {}°; bins of equal projected solid angle; share of the reflected light in brackets",
        "{0} 本のウォークを θ₀ = {1}° で入射; ビンは投影立体角が等しい; 括弧内は反射光に占める割合",
    ),
    ("ω = {}; exact R (Chandrasekhar) = {}, {}, {}", "ω = {0}; チャンドラセカールの厳密解 R = {1}, {2}, {3}"),
    ("ω = {}; optical thickness {}; transmitted T = {}, {}, {}", "ω = {0}; 光学的厚さ {1}; 透過 T = {2}, {3}, {4}"),
    ("{} or more scatterings", "{0} 回以上の散乱"),
    ("{}–{} scatterings", "{0}–{1} 回の散乱"),
    ("{}: R = {}", "{0}: R = {1}"),
    ("{} (ℓ = {}): mean r = {} walk, {} Burley, {} dipole", "{0} (ℓ = {1}): 平均 r = ウォーク {2}, Burley {3}, ダイポール {4}"),
    (
        "{} walks in by diffuse transmission at one point; A = {}, {}, {}; the walk returns {}, {}, {}",
        "1 点から拡散透過で入る {0} 本のウォーク; A = {1}, {2}, {3}; ウォークが返すのは {4}, {5}, {6}",
    ),
    // Cost figures: rungs, references and the strip's caption, sentence by sentence. Last:
    // their short patterns (`box {}`) must not catch the longer messages above.
    ("{}: the {} ladder", "{0}: {1}"),
    ("map {}", "マップ {0}"),
    ("ray {}", "シャドウレイ {0}"),
    ("volume {}", "シャドウボリューム {0}"),
    ("polygons {}", "影ポリゴン {0}"),
    ("ray-cast shadows, {} segments", "レイキャストの影, 分割数 {0}"),
    ("pcf {}", "PCF {0}"),
    ("bias {}", "バイアス {0}"),
    ("uniform {}", "等間隔 {0}"),
    ("equiangular {}", "等角 {0}"),
    ("independent {}", "独立 {0}"),
    ("stratified {}", "層化 {0}"),
    ("sobol {}", "Sobol {0}"),
    ("by area {}", "面積で {0}"),
    ("by solid angle {}", "立体角で {0}"),
    ("samples {}", "サンプル {0}"),
    ("size {}", "解像度 {0}"),
    ("naive {}", "単純 {0}"),
    ("box {}", "ボックス投影 {0}"),
    ("bounces {}", "反射 {0} 回"),
    ("depth {}, {} paths", "深さ {0}, {1} 本のパス"),
    ("depth {}", "深さ {0}"),
    ("subdivisions {}", "細分割 {0}"),
    ("patch size {}", "パッチの大きさ {0}"),
    ("patch {}", "パッチ {0}"),
    ("iterations {}", "反復 {0} 回"),
    ("the exact ray cast ({}×{} samples a pixel)", "厳密なレイキャスト (1 画素 {0}×{1} サンプル)"),
    ("the finest rung, {}", "最も細かい段 ({0})"),
    ("Monte Carlo IBL, {} samples", "モンテカルロ IBL, {0} サンプル"),
    ("{} equiangular samples", "等角サンプル {0} 個"),
    ("{} samples a light", "光源 1 個あたり {0} サンプル"),
    ("{} samples", "{0} サンプル"),
    ("{} bounces", "{0} 回の反射"),
    ("{} paths", "{0} 本のパス"),
    ("bilinear, aa {}", "バイリニア, aa {0}"),
    (
        "Bottom: |error| against {}, black 0 → pale yellow ≥ {} (linear radiance, largest channel).",
        "下段: {0} に対する |誤差| (線形放射輝度, 最大のチャンネル)。黒が 0, 淡い黄色が {1} 以上。",
    ),
    ("Times: median of {} runs on {} threads (scene build + render).", "時間: {1} スレッドで {0} 回計った中央値 (シーンの構築 + 描画)。"),
    ("Note: {}.", "注意: {0}。"),
    (
        "the runs of one rung spread by up to {}% of its median: the machine was busy, so read the times (and the front they draw) with care, or time again with more runs",
        "1 つの段の計測が中央値の最大 {0}% ばらついた。マシンが混んでいたので, 時間 (とそれが描くフロント) は慎重に読むか, 回数を増やして計り直すこと",
    ),
    ("|difference| from the first cell, {} layer", "最初のセルとの |差| ({0}レイヤー)"),
    ("roughness {}", "粗さ {0}"),
    // A legend entry with its share: the shortest pattern of all, so the very last.
    ("{} ({}%)", "{0} ({1}%)"),
    // `explain`: the photon passes' parts joined by "; " (last: any earlier template fits first).
    ("{}; {}", "{0}。{1}"),
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
        assert_eq!(Lang::Ja.tr("Gouraud"), "グロー (Gouraud)", "the lecture's spelling, the Latin name beside it");
        assert_eq!(Lang::Ja.tr("specular term"), "鏡面反射成分");
        assert_eq!(Lang::Ja.tr("K_shi = 50"), "K_shi = 50", "notation is not translated");
        assert_eq!(Lang::Ja.tr("Passes"), "パス");
        assert_eq!(Lang::Ja.tr("|difference|"), "|差|");
        // Every id is listed once.
        for (i, (en, _)) in JA.iter().enumerate() {
            assert!(!JA[..i].iter().any(|(e, _)| e == en), "{en} twice");
        }
    }

    #[test]
    fn messages_with_values_keep_their_values_and_translate_their_phrases() {
        let ja = |s: &str| Lang::Ja.say(s);
        assert_eq!(ja("114 vertices to clip space"), "頂点 114 個をクリップ空間へ");
        // Plural "s" holes are dropped; singular and plural give one Japanese form.
        assert_eq!(ja("BVH over 14 triangles; any-hit shadow rays for 1 light"), "三角形 14 個の BVH; 光源 1 個への any-hit シャドウレイ");
        assert_eq!(ja("BVH over 96 triangles; any-hit shadow rays for 2 lights"), "三角形 96 個の BVH; 光源 2 個への any-hit シャドウレイ");
        // A hole that is itself a phrase of the tables is translated too, recursively.
        assert_eq!(ja("light 0 (directional)"), "光源 0 (平行光源)");
        assert_eq!(
            ja(
                "no [environment]: mirrors and glass see the scene and the background colour; BVH for environment visibility and mirror rays"
            ),
            "[environment] がない: 鏡とガラスにはシーンと背景色が映る; 環境の可視判定と鏡のレイに BVH"
        );
        assert_eq!(ja("hemicube 64²"), "ヘミキューブ 64²");
        // Words of the user's and notation pass through; English never changes.
        assert_eq!(ja("my own title: 3 spheres"), "my own title: 3 spheres");
        assert_eq!(ja("K_spec = 0"), "K_spec = 0");
        assert_eq!(Lang::En.say("114 vertices to clip space"), "114 vertices to clip space");
    }

    #[test]
    fn every_template_names_only_holes_it_has_and_is_listed_once() {
        for (i, (en, ja)) in TEMPLATES.iter().enumerate() {
            let holes = en.matches("{}").count();
            assert!(holes > 0 && !en.contains("{}{}"), "{en}: a template needs holes with text between them");
            assert!(ja.contains("{0}") || holes == 0, "{en}: its first value is dropped");
            for k in holes..holes + 3 {
                assert!(!ja.contains(&format!("{{{k}}}")), "{en}: the translation names hole {k} it does not have");
            }
            assert!(!TEMPLATES[..i].iter().any(|(e, _)| e == en), "{en} twice");
            assert!(!JA.iter().any(|(e, _)| e == en), "{en} is a label and a template");
        }
    }
}
