//! Named conductors for `preset = "gold"`: the complex index of refraction η + iκ per RGB
//! channel, from published measurements.
//!
//! Source: Mitsuba 0.6's tabulated spectra (`data/ior/*.spd`, from the luxpop.com database:
//! Au, Ag, Cu, Al, Cr; Ni from Palik, *Handbook of Optical Constants of Solids*, 1985),
//! sampled at 650 nm (R), 550 nm (G) and 450 nm (B) with linear interpolation between the
//! tabulated wavelengths. Single wavelengths, not a CIE-weighted average: the values are
//! the textbook's "η at red, green, blue", and the F0 they give is in the test below.

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
pub const METALS: [Metal; 6] = [
    Metal { name: "gold", eta: Vec3::new(0.1678, 0.3504, 1.5085), k: Vec3::new(3.1378, 2.7141, 1.8788) },
    Metal { name: "silver", eta: Vec3::new(0.1394, 0.1248, 0.1517), k: Vec3::new(4.1288, 3.3396, 2.4704) },
    Metal { name: "copper", eta: Vec3::new(0.2166, 0.9582, 1.1658), k: Vec3::new(3.6377, 2.5771, 2.3939) },
    Metal { name: "aluminium", eta: Vec3::new(1.4748, 0.9586, 0.6180), k: Vec3::new(7.7941, 6.6870, 5.4694) },
    Metal { name: "chromium", eta: Vec3::new(3.6375, 3.1158, 1.9277), k: Vec3::new(4.3644, 4.4228, 4.1675) },
    Metal { name: "nickel", eta: Vec3::new(2.0140, 1.7724, 1.6288), k: Vec3::new(3.8079, 3.2526, 2.6540) },
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
