//! Hints and names for messages: did-you-mean, what a key means, which keys a variant reads.

use crate::lesson::kinds::{LightType, ModelKind, ShapeKind};
use crate::lesson::path::{KeyPath, Segment};

/// The names of the `[material.NAME]` tables of a parsed lesson.
pub(super) fn material_names(table: &toml::Table) -> Vec<String> {
    table.get("material").and_then(toml::Value::as_table).map(|m| m.keys().cloned().collect()).unwrap_or_default()
}

/// For an unknown key at `path` inside a material, light or object: the entry's variant
/// (`model `phong``) and the keys it reads, from the entry's `model`, `kind` or `shape`.
pub(super) fn variant_keys(table: &toml::Table, path: &KeyPath) -> Option<(String, Vec<&'static str>)> {
    let [Segment::Key(section), entry, Segment::Key(_)] = &path.0[..] else { return None };
    let get = |t: &toml::Table, k: &str| t.get(k).and_then(toml::Value::as_str).map(str::to_string);
    let entry_table = match (section.as_str(), entry) {
        ("material", Segment::Key(name)) => table.get("material")?.as_table()?.get(name)?.as_table()?,
        ("light" | "object", Segment::Index(i)) => table.get(section.as_str())?.as_array()?.get(*i)?.as_table()?,
        _ => return None,
    };
    match section.as_str() {
        "material" => {
            let model = get(entry_table, "model")?;
            let own = ModelKind::parse(&model)?.keys();
            let keys = ["model"].into_iter().chain(["ambient"]).chain(own.iter().copied()).chain(["emission"]).collect();
            Some((format!("model `{model}`"), keys))
        }
        "light" => {
            let kind = get(entry_table, "kind")?;
            let own = LightType::parse(&kind)?.keys();
            Some((format!("a `{kind}` light"), ["kind", "color", "intensity"].into_iter().chain(own.iter().copied()).collect()))
        }
        _ => {
            let shape = get(entry_table, "shape")?;
            let own = ShapeKind::parse(&shape)?.keys();
            let keys = ["shape", "material"]
                .into_iter()
                .chain(own.iter().copied())
                .chain(["translate", "rotate_deg", "scale", "crease_deg"])
                .collect();
            Some((format!("shape `{shape}`"), keys))
        }
    }
}

/// The keys serde knows for `T` (read from its unknown-field error, so never out of date).
pub(super) fn schema_fields<T: serde::de::DeserializeOwned>() -> Vec<String> {
    let mut probe = toml::Table::new();
    probe.insert("\u{1}".into(), toml::Value::Integer(0));
    match toml::Value::Table(probe).try_into::<T>() {
        Err(e) => e.message().split('`').skip(3).step_by(2).map(str::to_string).collect(),
        Ok(_) => Vec::new(),
    }
}

/// The last key of a path (`shininess` in `material.plastic.shininess`, `size` in `camera.size.0`).
pub(super) fn last_key(path: &KeyPath) -> Option<&str> {
    path.0.iter().rev().find_map(|s| match s {
        Segment::Key(k) => Some(k.as_str()),
        Segment::Index(_) => None,
    })
}

/// What a key means and a typical value, for hints on wrong values; `None` for keys whose
/// message says enough.
pub(super) fn key_help(path: &KeyPath) -> Option<String> {
    let section = match path.0.first() {
        Some(Segment::Key(k)) => k.as_str(),
        _ => return None,
    };
    let key = last_key(path)?;
    let coefficient = |symbol: &str| {
        format!(
            "`{key}` is {symbol}, a reflectance from 0 to 1 per channel: one number (0.8) or [r, g, b] such as [0.8, 0.2, 0.2]; to brighten the image, raise the light's intensity"
        )
    };
    let unit_weight = || format!("`{key}` is a weight from 0 to 1 (Disney's principled parameters); 0 turns it off");
    let text = match (section, key) {
        ("render", "aa") => {
            "aa is supersamples per pixel side (aa² samples per pixel, averaged); 2 or 4 smooths edges, 1 is fastest".into()
        }
        ("render", "spp") => {
            "spp is paths per pixel sample (aa² × spp paths a pixel): 16 previews, 256 is smooth, noise falls as 1/√spp".into()
        }
        ("render", "max_depth") => {
            "max_depth is the longest path in segments from the camera: 1 sees emitters, 2 adds direct light, 3 one bounce; 16 is the default".into()
        }
        ("render", "exposure") => "exposure is in stops: +1 doubles the brightness, -1 halves it, 0 leaves it".into(),
        ("camera", "size") => "size is [width, height] in pixels, e.g. [512, 512] (or --size 512x512)".into(),
        ("camera", "fov_deg") => "fov_deg is the vertical field of view in degrees; 30 to 60 looks natural (default 40)".into(),
        ("camera", "near") => "near is the clipping distance in front of the eye; 0.05 suits most scenes".into(),
        ("camera", "background") => "background is a linear RGB colour: one number for a grey (0.05) or [r, g, b]".into(),
        ("camera", "position" | "look_at" | "up") => format!("`{key}` is a point or direction [x, y, z], e.g. [0, 1, 5]"),
        ("object", "segments") => "segments are the columns around the y axis; 32 to 64 looks round (default 32, torus 48)".into(),
        ("object", "rings") => "rings are the latitude bands from pole to pole; 16 to 32 looks round (default 16)".into(),
        ("object", "sides") => "sides are the segments around the torus's tube; 16 to 32 looks round (default 24)".into(),
        ("object", "subdivisions") => "each subdivision splits every triangle in four (20·4ⁿ triangles); 3 looks round (default 3)".into(),
        ("object", "major_radius" | "minor_radius") => format!("`{key}` is a length in scene units (defaults 1 and 0.35)"),
        ("object", "translate") => "translate is [x, y, z] in scene units, e.g. [0, 1, 0]".into(),
        ("object", "rotate_deg") => "rotate_deg is [x, y, z] in degrees, e.g. [0, 45, 0]".into(),
        ("object", "crease_deg") => "crease_deg is the auto-smooth angle in degrees, 0 to 180, e.g. 30 (edges sharper than it stay sharp)".into(),
        ("object", "scale") => "scale is one positive number or [x, y, z], e.g. 2; mirror an object with rotate_deg instead".into(),
        ("material", "diffuse") => coefficient("K_diff (or the albedo ρ)"),
        ("material", "ambient") => coefficient("K_amb"),
        ("material", "specular") => coefficient("K_spec"),
        ("material", "base_color") => coefficient("the base colour"),
        ("material", "shininess") => {
            "shininess is the exponent K_shi: 1 to 10 is a broad highlight, 100 or more a small sharp one; 32 is typical".into()
        }
        ("material", "emission") => {
            "emission is light the surface gives off, a linear colour from 0 up: 0 for none, e.g. [1, 0.8, 0.5]".into()
        }
        ("material", "roughness") => "roughness goes from 0 (a mirror) to 1 (matte); α = roughness², 0.3 to 0.6 is typical".into(),
        ("material", "alpha") => "alpha is the microfacet α from 0 to 1 (α = roughness²), e.g. 0.25".into(),
        ("material", "ior") => "ior is the relative index of refraction η: 1.5 for glass and plastic, 1.33 for water".into(),
        ("material", "eta" | "k") => {
            "a conductor's complex index per channel, e.g. gold: eta = [0.143, 0.374, 1.442], k = [3.983, 2.385, 1.603]".into()
        }
        ("material", "subsurface_radius") => {
            "subsurface_radius is the mean free path per channel under the surface, [r, g, b] from 0 (Blender's Subsurface Radius), e.g. skin [1.0, 0.2, 0.1]".into()
        }
        ("material", "subsurface_scale") => "subsurface_scale multiplies subsurface_radius into world units, from 0, e.g. 0.05".into(),
        ("material", "sigma_deg") => "sigma_deg is the facet slope deviation σ in degrees: 0 is Lambert, 20 to 40 a rough clay".into(),
        (
            "material",
            "metallic" | "specular_tint" | "sheen" | "sheen_tint" | "clearcoat" | "clearcoat_gloss" | "subsurface" | "anisotropic",
        ) => unit_weight(),
        ("light", "intensity") => {
            "intensity scales the light's colour: 1 is the default; a point light with 1/r² falloff needs more, e.g. 10".into()
        }
        ("light", "color") => "color is a linear RGB colour: 1 for white or [r, g, b], e.g. [1, 0.9, 0.8]".into(),
        ("light", "ambient") => "this light's ambient part L_amb, a linear colour, e.g. 0.05".into(),
        ("light", "position") => "position is where the light is, [x, y, z], e.g. [2, 3, 4]".into(),
        ("light", "direction") => "direction is the way the light travels, [x, y, z]: [0, -1, 0] shines straight down".into(),
        ("light", "attenuation") => {
            "attenuation is [S_c, S_l, S_q] in d = 1/(S_c + S_l r + S_q r²): [1, 0, 0] is none, [0, 0, 1] is 1/r²".into()
        }
        ("light", "exponent") => "exponent is the spot's L_exp: 1 is a soft cone, 20 or more a tight one".into(),
        ("light", "cutoff_deg") => "cutoff_deg is the spot cone's half-angle in degrees, e.g. 30".into(),
        ("light", "samples") => {
            "samples is how many points of the light each shaded point takes: 16 is a soft, slightly grainy penumbra, 64 to 256 a smooth one".into()
        }
        ("light", "radius") => "radius is the size of the disk, sphere or tube in world units, e.g. 0.25".into(),
        ("light", "ground_color") => "ground_color is the sky light's radiance from below the horizon, a linear colour, e.g. [0.2, 0.15, 0.1]".into(),
        ("render", "shadow_map_size") => {
            "shadow_map_size is the texels per side of each shadow map: 256 is blocky, 1024 is the default, 4096 is fine".into()
        }
        ("render", "shadow_bias") => {
            "shadow_bias is in world units along the light: 0 shows acne, 0.005 is the default, too much detaches the shadow".into()
        }
        ("render", "shadow_slope_bias") => "shadow_slope_bias multiplies tan θ (more bias where light grazes), e.g. 0.01".into(),
        ("render", "shadow_normal_offset") => "shadow_normal_offset moves the looked-up point along its normal, in texels, e.g. 1".into(),
        ("render", "shadow_pcf") => "shadow_pcf is the filter width in texels: 1 is one bilinear compare, 3 to 9 soften the edge".into(),
        ("fog", "steps") => format!(
            "steps is the ray-march steps per sample, 1 to {} (the limit): 16 is grainy, 64 the default, 512 close to exact",
            crate::lesson::limits::MAX_FOG_STEPS
        ),
        ("fog", "sigma_s" | "sigma_a") => {
            "sigma_s and sigma_a are scattering and absorption per unit length, ≥ 0: 0.05 is a light haze, 0.5 a thick fog".into()
        }
        ("fog", "density") => "density is per unit length, ≥ 0: f = e^(−density·z) (exp) or e^(−(density·z)²) (exp2), e.g. 0.1".into(),
        ("fog", "start" | "end") => "start and end are eye distances with start < end: no fog nearer than start, all fog beyond end".into(),
        ("fog", "g") => "g is the Henyey-Greenstein asymmetry, strictly between −1 and 1: 0 isotropic, 0.7 forward".into(),
        ("scene", "ambient") => "ambient is L_glob, the global ambient light, a linear colour; 0.05 to 0.2 lifts the shadows".into(),
        ("figure", "cell") => "cell is [width, height] of each cell in pixels, e.g. [256, 256]".into(),
        ("figure", "incidence") => "incidence lists angles from the normal in degrees, e.g. [30, 60]".into(),
        ("figure", "swap") => "swap = true also draws every lobe with l and v exchanged in f (reciprocity)".into(),
        ("figure", "terms") => "terms lists Cook-Torrance partial products, e.g. [\"D\", \"DG\", \"DGF\"]".into(),
        ("figure", "repeat") => "repeat is the timed runs per rung (the median is shown), e.g. 5".into(),
        _ => return None,
    };
    Some(text)
}

/// A duplicate key: which one, where it was first set, and how to fix it. `span` is the
/// second occurrence (a key, or a table header's last part).
pub(super) fn duplicate_key(text: &str, span: std::ops::Range<usize>) -> (String, String) {
    let generic = ("not valid TOML: duplicate key".to_string(), "a key can appear only once in a table; remove one of the two".to_string());
    let Some(raw) = text.get(span.clone()) else { return generic };
    let name = raw.trim().trim_matches(['"', '\'']).to_string();
    if name.is_empty() {
        return generic;
    }
    let line_start = text[..span.start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[span.start..].find('\n').map_or(text.len(), |i| span.start + i);
    let this_line = text[line_start..line_end].trim();
    let lines: Vec<&str> = text.lines().collect();
    let here = text[..span.start].matches('\n').count();
    let is_header = |l: &str| l.trim_start().starts_with('[');
    if is_header(this_line) {
        // `[material.plastic]` twice: the header text identifies the table.
        let header = this_line.split('#').next().unwrap_or("").trim();
        let first = lines[..here].iter().position(|l| l.split('#').next().unwrap_or("").trim() == header);
        let at = first.map_or(String::new(), |i| format!(" (first on line {})", i + 1));
        let inner = header.trim_start_matches('[').trim_end_matches(']');
        return (
            format!("not valid TOML: duplicate key: table `{header}` is defined twice{at}"),
            format!("put all the keys of `{inner}` under one `{header}` header"),
        );
    }
    // A key: find its table (the last header above) and the earlier line setting it.
    let table_start = lines[..here].iter().rposition(|l| is_header(l)).map_or(0, |i| i + 1);
    let table = lines[..here].iter().rev().find(|l| is_header(l)).map(|l| l.split('#').next().unwrap_or("").trim().to_string());
    let sets_key = |l: &str| {
        let t = l.trim_start();
        let t = t.strip_prefix(raw.trim()).or_else(|| t.strip_prefix(name.as_str()));
        t.is_some_and(|rest| rest.trim_start().starts_with(['=', '.']))
    };
    let first = (table_start..here).find(|&i| sets_key(lines[i]));
    let place = table.map_or("at the top level".to_string(), |t| format!("in `{t}`"));
    let at = first.map_or(String::new(), |i| format!(", first set on line {}", i + 1));
    (
        format!("not valid TOML: duplicate key `{name}` {place}{at}"),
        format!("a key can appear only once in a table; keep one of the two `{name}` lines"),
    )
}

/// A hint for the TOML syntax errors beginners meet most; the reference otherwise.
pub(super) fn toml_hint(message: &str) -> &'static str {
    if message.contains("must be quoted") {
        "text values need quotes, e.g. model = \"phong\""
    } else if message.contains("duplicate key") {
        "a key can appear only once in a table; remove one of the two"
    } else {
        "see docs/lesson-format.md for the syntax of a lesson"
    }
}

/// The closest allowed name when it is close enough to be a typo, differs only in case
/// (`ggx` → `GGX`), or is an allowed one without its unit suffix (`fov` → `fov_deg`,
/// `rotate` → `rotate_deg`).
pub(crate) fn suggest<'s>(got: &str, allowed: &[&'s str]) -> Option<&'s str> {
    if let Some(same) = allowed.iter().find(|a| a.eq_ignore_ascii_case(got)) {
        return Some(same);
    }
    let close = allowed
        .iter()
        .map(|a| (strsim::damerau_levenshtein(got, a), *a))
        .filter(|(d, a)| *d <= 2.max(a.len() / 4) && *d < a.len())
        .min_by_key(|(d, _)| *d)
        .map(|(_, a)| a);
    close.or_else(|| allowed.iter().copied().find(|a| got.len() >= 3 && a.strip_prefix(got).is_some_and(|rest| rest.starts_with('_'))))
}
