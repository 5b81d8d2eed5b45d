//! The lesson pages' equations in MathML (native in browsers: no script, no network), one
//! entry per shading model a lesson's materials use. Each is the form docs/models.md gives,
//! in the course's notation.

use crate::shading::brdf::Brdf;
use crate::shading::material::{ClassicModel, Material, Model};

/// One displayed equation: what it is, its source, and the MathML `<math>` element.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Equation {
    /// Which model (a heading on the page).
    pub name: &'static str,
    /// Where the equation comes from.
    pub source: &'static str,
    /// The `<math display="block">` element.
    pub mathml: String,
}

fn mi(s: &str) -> String {
    format!("<mi>{s}</mi>")
}
fn mo(s: &str) -> String {
    format!("<mo>{s}</mo>")
}
fn mn(s: &str) -> String {
    format!("<mn>{s}</mn>")
}
fn row(parts: &[String]) -> String {
    format!("<mrow>{}</mrow>", parts.concat())
}
fn sub(base: &str, s: &str) -> String {
    format!("<msub><mi>{base}</mi><mi>{s}</mi></msub>")
}
fn sup(base: String, s: String) -> String {
    format!("<msup>{base}{s}</msup>")
}
fn subsup(base: &str, s: &str, p: &str) -> String {
    format!("<msubsup><mi>{base}</mi><mi>{s}</mi><mi>{p}</mi></msubsup>")
}
fn frac(n: String, d: String) -> String {
    format!("<mfrac>{n}{d}</mfrac>")
}
fn paren(inner: String) -> String {
    row(&[mo("("), inner, mo(")")])
}
fn max0(a: &str, b: &str) -> String {
    row(&[mi("max"), paren(row(&[mi(a), mo("·"), mi(b), mo(","), mn("0")]))])
}
fn math(body: String) -> String {
    format!("<math display=\"block\">{body}</math>")
}

/// The course's illumination equation for a classic model (`spec`: its specular term).
fn classic(model: ClassicModel) -> Equation {
    let otimes = || mo("⊗");
    let spec = match model {
        ClassicModel::Lambert => String::new(),
        ClassicModel::Phong => row(&[mo("+"), sup(max0("R", "V"), sub("K", "shi")), sub("K", "spec"), otimes(), subsup("L", "spec", "k")]),
        ClassicModel::BlinnPhong => {
            row(&[mo("+"), sup(max0("N", "H"), sub("K", "shi")), sub("K", "spec"), otimes(), subsup("L", "spec", "k")])
        }
    };
    let inner = row(&[
        sub("K", "amb"),
        otimes(),
        subsup("L", "amb", "k"),
        mo("+"),
        sup(mi("d"), mi("k")),
        paren(row(&[max0("N", "L"), sub("K", "diff"), otimes(), subsup("L", "diff", "k"), spec])),
    ]);
    let body = row(&[
        mi("I"),
        mo("="),
        sub("L", "glob"),
        otimes(),
        sub("K", "amb"),
        mo("+"),
        sub("L", "emi"),
        mo("+"),
        "<munder><mo>∑</mo><mi>k</mi></munder>".into(),
        subsup("C", "spot", "k"),
        row(&[mo("{"), inner, mo("}")]),
    ]);
    let (name, source) = match model {
        ClassicModel::Lambert => ("Lambert (the course's equation, diffuse only)", "the course notes; docs/models.md"),
        ClassicModel::Phong => ("Phong (the course's equation), R = 2(N·L)N − L", "Phong 1975; docs/models.md"),
        ClassicModel::BlinnPhong => ("Blinn-Phong (the course's equation), H = (L + V)/|L + V|", "Blinn 1977; docs/models.md"),
    };
    Equation { name, source, mathml: math(body) }
}

/// The reflected radiance of every physically based material.
fn physical() -> Equation {
    let body = row(&[
        sub("L", "o"),
        mo("="),
        sub("K", "amb"),
        mo("⊗"),
        sub("L", "glob"),
        mo("+"),
        sub("L", "emi"),
        mo("+"),
        "<munder><mo>∑</mo><mi>k</mi></munder>".into(),
        subsup("C", "spot", "k"),
        mi("f"),
        paren(row(&[mi("l"), mo(","), mi("v")])),
        sub("E", "k"),
        paren(row(&[mi("n"), mo("·"), mi("l")])),
    ]);
    Equation {
        name: "Physically based: reflected radiance (E = irradiance at normal incidence)",
        source: "docs/models.md",
        mathml: math(body),
    }
}

/// The BRDF f of a physically based material.
fn brdf(b: &Brdf) -> Equation {
    let pi = || mi("π");
    let (name, source, body) = match b {
        Brdf::Diffuse(_) => ("Lambert BRDF", "Lambert 1760; docs/models.md", row(&[mi("f"), mo("="), frac(mi("ρ"), pi())])),
        Brdf::CookTorrance(_) => (
            "Cook-Torrance microfacet BRDF (D: distribution, F: Fresnel, G: masking-shadowing)",
            "Cook & Torrance 1982; Walter et al. 2007; docs/models.md",
            row(&[
                mi("f"),
                mo("="),
                frac(
                    row(&[
                        mi("D"),
                        paren(mi("h")),
                        mi("F"),
                        paren(row(&[mi("v"), mo("·"), mi("h")])),
                        mi("G"),
                        paren(row(&[mi("l"), mo(","), mi("v")])),
                    ]),
                    row(&[mn("4"), paren(row(&[mi("n"), mo("·"), mi("l")])), paren(row(&[mi("n"), mo("·"), mi("v")]))]),
                ),
            ]),
        ),
        Brdf::OrenNayar(_) => (
            "Oren-Nayar rough diffuse (qualitative model), A = 1 − 0.5σ²/(σ² + 0.33), B = 0.45σ²/(σ² + 0.09)",
            "Oren & Nayar 1994; docs/models.md",
            row(&[
                mi("f"),
                mo("="),
                frac(mi("ρ"), pi()),
                row(&[
                    mo("["),
                    mi("A"),
                    mo("+"),
                    mi("B"),
                    mi("max"),
                    paren(row(&[mn("0"), mo(","), mi("cos"), mi("Δφ")])),
                    mi("sin"),
                    mi("α"),
                    mi("tan"),
                    mi("β"),
                    mo("]"),
                ]),
            ]),
        ),
        Brdf::Principled(_) => (
            "Disney principled BRDF: a retro-reflective diffuse lobe plus a GGX specular lobe",
            "Burley 2012; docs/models.md",
            row(&[
                mi("f"),
                mo("="),
                sub("f", "d"),
                mo("+"),
                frac(
                    row(&[
                        mi("D"),
                        paren(mi("h")),
                        mi("F"),
                        paren(row(&[mi("v"), mo("·"), mi("h")])),
                        mi("G"),
                        paren(row(&[mi("l"), mo(","), mi("v")])),
                    ]),
                    row(&[mn("4"), paren(row(&[mi("n"), mo("·"), mi("l")])), paren(row(&[mi("n"), mo("·"), mi("v")]))]),
                ),
            ]),
        ),
        Brdf::NormalizedPhong(_) => (
            "Normalized Phong",
            "Lewis 1994; Lafortune & Willems 1994; docs/models.md",
            row(&[
                mi("f"),
                mo("="),
                frac(sub("k", "d"), pi()),
                mo("+"),
                sub("k", "s"),
                frac(row(&[mi("n"), mo("+"), mn("2")]), row(&[mn("2"), pi()])),
                sup(max0("R", "V"), mi("n")),
            ]),
        ),
        Brdf::NormalizedBlinnPhong(_) => (
            "Normalized Blinn-Phong",
            "Akenine-Möller, Haines & Hoffman, Real-Time Rendering 3rd ed., §7.6; docs/models.md",
            row(&[
                mi("f"),
                mo("="),
                frac(sub("k", "d"), pi()),
                mo("+"),
                sub("k", "s"),
                frac(row(&[mi("n"), mo("+"), mn("8")]), row(&[mn("8"), pi()])),
                sup(max0("N", "H"), mi("n")),
            ]),
        ),
    };
    Equation { name, source, mathml: math(body) }
}

/// A perfect mirror.
fn mirror() -> Equation {
    let body = row(&[
        sub("L", "o"),
        mo("="),
        sub("L", "emi"),
        mo("+"),
        mi("tint"),
        mo("⊗"),
        sub("L", "i"),
        paren(mi("r")),
        mo(","),
        mspace(),
        mi("r"),
        mo("="),
        mn("2"),
        paren(row(&[mi("n"), mo("·"), mi("v")])),
        mi("n"),
        mo("−"),
        mi("v"),
    ]);
    Equation { name: "Mirror (L_i: the environment or the object the reflected ray hits)", source: "docs/models.md", mathml: math(body) }
}

/// Smooth glass: Fresnel-weighted reflection and Snell refraction (docs/models.md, "Glass").
fn glass() -> Equation {
    let body = row(&[
        sub("L", "o"),
        mo("="),
        sub("L", "emi"),
        mo("+"),
        mi("F"),
        sub("L", "i"),
        paren(mi("r")),
        mo("+"),
        paren(row(&[mn("1"), mo("−"), mi("F")])),
        mi("tint"),
        mo("⊗"),
        sub("L", "i"),
        paren(mi("t")),
        mo(","),
        mspace(),
        sub("n", "1"),
        mi("sin"),
        sub("θ", "1"),
        mo("="),
        sub("n", "2"),
        mi("sin"),
        sub("θ", "2"),
    ]);
    Equation { name: "Glass (F: exact dielectric Fresnel; total internal reflection: F = 1)", source: "docs/models.md", mathml: math(body) }
}

fn mspace() -> String {
    "<mspace width=\"1em\"/>".into()
}

/// The equations of `materials`, each model once, in the order the materials name them.
pub fn equations(materials: &[Material]) -> Vec<Equation> {
    let mut out: Vec<Equation> = Vec::new();
    let mut push = |e: Equation| {
        if !out.iter().any(|o| o.name == e.name) {
            out.push(e);
        }
    };
    for m in materials {
        match &m.model {
            Model::Classic(c) => push(classic(c.model)),
            Model::Physical(b) => {
                push(physical());
                push(brdf(b));
            }
            Model::Mirror(_) => push(mirror()),
            Model::Glass(_) => push(glass()),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every element opened is closed, so a browser parses each equation as written.
    #[test]
    fn mathml_is_balanced() {
        let all = [
            classic(ClassicModel::Lambert),
            classic(ClassicModel::Phong),
            classic(ClassicModel::BlinnPhong),
            physical(),
            mirror(),
            glass(),
        ];
        for e in all {
            for tag in ["mrow", "msub", "msup", "msubsup", "mfrac", "mi", "mo", "mn", "munder", "math"] {
                let open = e.mathml.matches(&format!("<{tag}>")).count() + e.mathml.matches(&format!("<{tag} ")).count();
                let close = e.mathml.matches(&format!("</{tag}>")).count();
                assert_eq!(open, close, "{tag} in {}", e.name);
            }
        }
    }
}
