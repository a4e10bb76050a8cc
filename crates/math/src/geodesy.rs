//! Geodesy on a sphere: where a point lies given its east/north offset from an origin, and
//! the offset of a point from an origin (its inverse).
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

/// East and north offsets (m) of the point at `latitude_deg`, `longitude_deg` from the origin
/// at `origin_latitude_deg`, `origin_longitude_deg`, on a sphere of radius `radius` (m): the
/// inverse of [`destination`]. The great-circle distance comes from the haversine formula
/// (numerically sound for short distances) and the initial bearing from
/// `atan2(sin Δλ cos φ₂, cos φ₁ sin φ₂ − sin φ₁ cos φ₂ cos Δλ)`; the offsets are the distance
/// along that bearing resolved east and north (Sinnott 1984, "Virtues of the haversine", Sky
/// and Telescope 68(2):159; the bearing as in Williams, *Aviation Formulary*).
#[must_use]
pub fn offset(
    origin_latitude_deg: f64,
    origin_longitude_deg: f64,
    latitude_deg: f64,
    longitude_deg: f64,
    radius: f64,
) -> (f64, f64) {
    let (lat1, lat2) = (origin_latitude_deg.to_radians(), latitude_deg.to_radians());
    let dlat = lat2 - lat1;
    let dlon = (longitude_deg - origin_longitude_deg).to_radians();
    let h = (0.5 * dlat).sin().powi(2) + lat1.cos() * lat2.cos() * (0.5 * dlon).sin().powi(2);
    let distance = 2.0 * radius * h.sqrt().min(1.0).asin();
    let bearing = (dlon.sin() * lat2.cos())
        .atan2(lat1.cos() * lat2.sin() - lat1.sin() * lat2.cos() * dlon.cos());
    (distance * bearing.sin(), distance * bearing.cos())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_inverts_destination() {
        let r = 6_378_137.0;
        for (east, north) in [
            (1500.0, -320.0),
            (-40.0, 2.5),
            (0.0, 9000.0),
            (-7000.0, -7000.0),
        ] {
            let (lat, lon) = destination(-23.5, -46.6, east, north, r);
            let (e, n) = offset(-23.5, -46.6, lat, lon, r);
            assert!(
                (e - east).abs() < 1e-6 && (n - north).abs() < 1e-6,
                "{e} {n}"
            );
        }
        assert_eq!(offset(45.0, 7.0, 45.0, 7.0, r), (0.0, 0.0));
    }

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
