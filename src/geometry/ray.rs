//! A ray and the nearest hit along it.

use glam::DVec3;

/// The half-line `origin + t·dir`, t ≥ 0 (`dir` need not be unit length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: DVec3,
    /// Its direction; `t` is measured in multiples of it.
    pub dir: DVec3,
}

impl Ray {
    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.dir * t
    }
}

/// Where a ray met a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Ray parameter of the hit.
    pub t: f64,
    /// Unit outward world normal there.
    pub n: DVec3,
    /// Which surface was hit (an index the caller chose, e.g. a material).
    pub id: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn at_walks_along_the_direction() {
        let r = Ray { origin: DVec3::new(1.0, 0.0, 0.0), dir: DVec3::new(0.0, 2.0, 0.0) };
        assert_eq!(r.at(0.0), r.origin);
        assert_eq!(r.at(1.5), DVec3::new(1.0, 3.0, 0.0));
    }
}
