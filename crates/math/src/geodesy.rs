//! Geodesy on a sphere: where a point lies given its east/north offset from an origin.
//!
//! karman's flights and dispersion studies live in a flat launch frame (x east, y north);
//! their latitude/longitude outputs (trajectory, KML) use the great-circle destination on a
//! sphere of the datum's local radius, as RocketPy 1.13 does (`tools.inverted_haversine`;
//! docs/physics.md §4.6, §11, §12.2).

/// Latitude and longitude (deg) of the point `east`, `north` (m) from the origin at
/// `latitude_deg`, `longitude_deg`, on a sphere of radius `radius` (m): the inverted
/// haversine (great-circle destination) that RocketPy 1.13 uses for flight and dispersion
/// outputs (docs/physics.md §11, §12.2), with the drift `√(x² + y²)` and the bearing
/// `atan2(east, north)` from north.
#[must_use]
pub fn destination(
    latitude_deg: f64,
    longitude_deg: f64,
    east: f64,
    north: f64,
    radius: f64,
) -> (f64, f64) {
    let delta = east.hypot(north) / radius;
    let bearing = east.atan2(north);
    let lat1 = latitude_deg.to_radians();
    let lon1 = longitude_deg.to_radians();
    let lat2 = (lat1.sin() * delta.cos() + lat1.cos() * delta.sin() * bearing.cos()).asin();
    let lon2 = lon1
        + (bearing.sin() * delta.sin() * lat1.cos()).atan2(delta.cos() - lat1.sin() * lat2.sin());
    (lat2.to_degrees(), lon2.to_degrees())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn destination_follows_great_circles() {
        let r = 6_371_000.0;
        let arc = r * 1f64.to_radians();
        // One degree of arc north along a meridian.
        let (lat, lon) = destination(10.0, 20.0, 0.0, arc, r);
        assert!(
            (lat - 11.0).abs() < 1e-12 && (lon - 20.0).abs() < 1e-12,
            "{lat} {lon}"
        );
        // One degree of arc east along the equator.
        let (lat, lon) = destination(0.0, 20.0, arc, 0.0, r);
        assert!(
            lat.abs() < 1e-12 && (lon - 21.0).abs() < 1e-12,
            "{lat} {lon}"
        );
        // South-west, and the origin maps onto itself.
        let (lat, lon) = destination(45.0, -100.0, -1000.0, -1000.0, r);
        assert!(lat < 45.0 && lon < -100.0);
        let (lat, lon) = destination(45.0, -100.0, 0.0, 0.0, r);
        assert!((lat - 45.0).abs() < 1e-12 && (lon + 100.0).abs() < 1e-12);
    }
}
