//! Named conductors for `preset = "gold"`: the complex index of refraction η + iκ per RGB
//! channel, from published measurements.
//!
//! Sources, each sampled at 650 nm (R), 550 nm (G) and 450 nm (B) with linear interpolation
//! between tabulated wavelengths:
//! - gold, silver, copper, aluminium, chromium: Mitsuba 0.6's tabulated spectra
//!   (`data/ior/*.spd`, from the luxpop.com database); nickel: Palik, *Handbook of Optical
//!   Constants of Solids*, 1985 (Mitsuba's `Ni_palik`);
//! - iron: Johnson & Christy, "Optical constants of transition metals", Phys. Rev. B 9,
//!   5056 (1974), as tabulated by refractiveindex.info (`main/Fe/nk/Johnson`);
//! - platinum: Rakić et al., Appl. Opt. 37, 5271 (1998), Lorentz-Drude fit, tabulated by
//!   refractiveindex.info (`main/Pt/nk/Rakic-LD`);
//! - titanium: the same paper's Lorentz-Drude model evaluated at the three wavelengths
//!   (ω_p 7.29 eV; f 0.148, 0.899, 0.393, 0.187, 0.001; Γ 0.082, 2.276, 2.518, 1.663,
//!   1.762 eV; ω_j 0.777, 1.545, 2.509, 19.43 eV; its fit starts at 470 nm, so blue is
//!   20 nm outside it).
//!
//! Single wavelengths, not a CIE-weighted average: the values are the textbook's "η at red,
//! green, blue", and the F0 they give is in the test below.

use glam::Vec3;

/// One named conductor: η and κ at 650, 550, 450 nm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Metal {
    /// The name in lesson files.
    pub name: &'static str,
    /// Real part η of the complex index (R, G, B).
    pub eta: Vec3,
    /// Extinction κ (R, G, B).
    pub k: Vec3,
}

/// Every preset, in the order messages list them (`aluminum` is an alias, see [`find`]).
pub const METALS: [Metal; 9] = [
    Metal { name: "gold", eta: Vec3::new(0.1678, 0.3504, 1.5085), k: Vec3::new(3.1378, 2.7141, 1.8788) },
    Metal { name: "silver", eta: Vec3::new(0.1394, 0.1248, 0.1517), k: Vec3::new(4.1288, 3.3396, 2.4704) },
    Metal { name: "copper", eta: Vec3::new(0.2166, 0.9582, 1.1658), k: Vec3::new(3.6377, 2.5771, 2.3939) },
    Metal { name: "aluminium", eta: Vec3::new(1.4748, 0.9586, 0.6180), k: Vec3::new(7.7941, 6.6870, 5.4694) },
    Metal { name: "chromium", eta: Vec3::new(3.6375, 3.1158, 1.9277), k: Vec3::new(4.3644, 4.4228, 4.1675) },
    Metal { name: "nickel", eta: Vec3::new(2.0140, 1.7724, 1.6288), k: Vec3::new(3.8079, 3.2526, 2.6540) },
    Metal { name: "iron", eta: Vec3::new(2.9114, 2.9497, 2.5845), k: Vec3::new(3.0893, 2.9318, 2.7670) },
    Metal { name: "titanium", eta: Vec3::new(2.0945, 1.7897, 1.3343), k: Vec3::new(3.1986, 3.0017, 2.7597) },
    Metal { name: "platinum", eta: Vec3::new(2.3700, 2.0909, 1.8510), k: Vec3::new(4.2535, 3.7038, 3.1396) },
];

/// The preset named `name` (any case; "aluminum" is "aluminium").
pub fn find(name: &str) -> Option<Metal> {
    let name = if name.eq_ignore_ascii_case("aluminum") { "aluminium" } else { name };
    METALS.into_iter().find(|m| m.name.eq_ignore_ascii_case(name))
}

/// The names a lesson may write, aliases included.
pub fn names() -> Vec<&'static str> {
    METALS.iter().map(|m| m.name).chain(["aluminum"]).collect()
}

/// Reflectance at normal incidence, ((η−1)² + κ²) / ((η+1)² + κ²) (Born & Wolf, §14.2).
pub fn f0(eta: Vec3, k: Vec3) -> Vec3 {
    let k2 = k * k;
    ((eta - 1.0) * (eta - 1.0) + k2) / ((eta + 1.0) * (eta + 1.0) + k2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shading::microfacet::fresnel::conductor_rgb;

    #[test]
    fn each_preset_reflects_at_normal_incidence_as_its_index_says() {
        for m in METALS {
            let f = f0(m.eta, m.k);
            // The exact conductor Fresnel at cos θ = 1 is the closed form F0.
            assert!((conductor_rgb(1.0, m.eta, m.k) - f).abs().max_element() < 1e-5, "{}: {f}", m.name);
            assert!(f.min_element() > 0.35 && f.max_element() < 0.99, "{}: metals reflect strongly, {f}", m.name);
        }
        // Gold is yellow: F0 ≈ (0.94, 0.85, 0.39), red > green > blue.
        let gold = f0(find("gold").unwrap().eta, find("gold").unwrap().k);
        assert!((gold - Vec3::new(0.940, 0.847, 0.386)).abs().max_element() < 2e-3, "{gold}");
        // Copper is red; silver and aluminium are nearly grey and bright.
        let cu = f0(find("copper").unwrap().eta, find("copper").unwrap().k);
        assert!(cu.x > 0.9 && cu.y < 0.7 && cu.z < 0.6, "{cu}");
        // Platinum against Hoffman's F0 table (SIGGRAPH 2013 course, "Physics and Math of
        // Shading"): (0.67, 0.64, 0.59), from a spectral integration of other data.
        let pt = f0(find("platinum").unwrap().eta, find("platinum").unwrap().k);
        assert!((pt - Vec3::new(0.67, 0.64, 0.59)).abs().max_element() < 0.015, "{pt}");
        // Iron and titanium are darker greys: F0 between 0.45 and 0.6 in every channel.
        for dark in ["iron", "titanium"] {
            let f = f0(find(dark).unwrap().eta, find(dark).unwrap().k);
            assert!(f.min_element() > 0.45 && f.max_element() < 0.6, "{dark}: {f}");
        }
        for grey in ["silver", "aluminium"] {
            let f = f0(find(grey).unwrap().eta, find(grey).unwrap().k);
            assert!(f.min_element() > 0.9 && f.max_element() - f.min_element() < 0.06, "{grey}: {f}");
        }
    }

    #[test]
    fn names_and_aliases_are_found_in_any_case() {
        assert_eq!(find("Aluminum"), find("aluminium"));
        assert_eq!(find("GOLD").map(|m| m.name), Some("gold"));
        assert_eq!(find("brass"), None);
        assert!(names().contains(&"aluminum"));
    }
}
