//! `dispersion.kml`: landing points and the apogee/landing ellipses for Google Earth
//! (OGC KML 2.2), positions from (x east, y north) offsets by the inverted haversine.

use crate::stats::{Ellipse, NORMAL_SIGMA_PROBABILITY, probability_scale};
use crate::study::Site;
use std::fmt::Write as _;

/// Latitude and longitude (degrees) of the point `x` m east and `y` m north of the site:
/// the great-circle destination at distance `sqrt(x² + y²)` and bearing `atan2(x, y)` from
/// north on a sphere of the site's radius (the inverted haversine of RocketPy's
/// `tools.inverted_haversine`; docs/physics.md §4.6, §12.2).
pub fn offset_to_lat_lon(site: &Site, x: f64, y: f64) -> (f64, f64) {
    karman_math::geodesy::destination(
        site.latitude_deg,
        site.longitude_deg,
        x,
        y,
        site.earth_radius,
    )
}

/// Points of each ellipse ring (docs/physics.md §12.2 uses 100).
const RING_POINTS: usize = 100;

/// Line colours (KML `aabbggrr`) of the 1σ, 2σ, 3σ contours: green, orange, red.
const COLOURS: [&str; 3] = ["ff00c000", "ff0090ff", "ff0000ff"];

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Icon colours (KML `aabbggrr`) of the landing points of the second, third, ... body of a
/// study of several (the first keeps the default icon): magenta, cyan, yellow, violet.
const BODY_COLOURS: [&str; 4] = ["ffff00ff", "ffffff00", "ff00ffff", "ffff0080"];

/// One body's ellipses and landing points in the KML document.
#[derive(Debug, Clone, Copy)]
pub struct Body<'a> {
    /// Its name; none in a study of one body.
    pub name: Option<&'a str>,
    /// (label, ellipse) pairs ("Apogee", "Landing").
    pub ellipses: &'a [(&'a str, Ellipse)],
    /// (sample index, [x, y]) landing points drawn.
    pub points: &'a [(u64, [f64; 2])],
    /// Landing points in all.
    pub points_total: u64,
}

/// The KML document: for each body its ellipses, in both conventions, and its landing
/// points; a named body's in a folder of its name, its points in a style of their own.
pub fn document(title: &str, site: &Site, bodies: &[Body<'_>]) -> String {
    let mut kml = String::new();
    let coordinates = |x: f64, y: f64| {
        let (lat, lon) = offset_to_lat_lon(site, x, y);
        format!("{lon:.8},{lat:.8},0")
    };
    // Writing into a String cannot fail.
    let _ = writeln!(
        kml,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n<Document>\n<name>{}</name>",
        escape(title)
    );
    for (level, colour) in COLOURS.iter().enumerate() {
        let _ = writeln!(
            kml,
            "<Style id=\"sigma{}\"><LineStyle><color>{colour}</color><width>2</width></LineStyle><PolyStyle><fill>0</fill></PolyStyle></Style>",
            level + 1
        );
    }
    let _ = writeln!(
        kml,
        "<Style id=\"point\"><IconStyle><scale>0.4</scale></IconStyle></Style>"
    );
    for index in 1..bodies.len() {
        let colour = BODY_COLOURS[(index - 1) % BODY_COLOURS.len()];
        let _ = writeln!(
            kml,
            "<Style id=\"point{index}\"><IconStyle><color>{colour}</color><scale>0.4</scale></IconStyle></Style>"
        );
    }
    for (index, body) in bodies.iter().enumerate() {
        if let Some(name) = body.name {
            let _ = writeln!(kml, "<Folder><name>{}</name>", escape(name));
        }
        write_body(&mut kml, body, index, &coordinates);
        if body.name.is_some() {
            let _ = writeln!(kml, "</Folder>");
        }
    }
    let _ = writeln!(kml, "</Document>\n</kml>");
    kml
}

/// The ellipse folders and the landing-point folder of body `index`.
fn write_body(
    kml: &mut String,
    body: &Body<'_>,
    index: usize,
    coordinates: &dyn Fn(f64, f64) -> String,
) {
    for (label, ellipse) in body.ellipses {
        for (convention, scales) in [
            ("k-sigma (RocketPy)", [1.0, 2.0, 3.0]),
            (
                "probability",
                NORMAL_SIGMA_PROBABILITY.map(probability_scale),
            ),
        ] {
            let _ = writeln!(
                kml,
                "<Folder><name>{} ellipses, {convention}</name>",
                escape(label)
            );
            for (level, k) in scales.into_iter().enumerate() {
                let name = if convention == "probability" {
                    format!("{:.2} %", 100.0 * NORMAL_SIGMA_PROBABILITY[level])
                } else {
                    format!("{} sigma", level + 1)
                };
                let mut ring = ellipse.boundary(k, RING_POINTS);
                if let Some(first) = ring.first().copied() {
                    ring.push(first);
                }
                let ring: Vec<String> = ring.iter().map(|p| coordinates(p[0], p[1])).collect();
                let _ = writeln!(
                    kml,
                    "<Placemark><name>{name}</name><styleUrl>#sigma{}</styleUrl><Polygon><outerBoundaryIs><LinearRing><coordinates>{}</coordinates></LinearRing></outerBoundaryIs></Polygon></Placemark>",
                    level + 1,
                    ring.join(" ")
                );
            }
            let _ = writeln!(kml, "</Folder>");
        }
    }
    let shown = if (body.points.len() as u64) < body.points_total {
        format!(" (first {} of {})", body.points.len(), body.points_total)
    } else {
        String::new()
    };
    let style = if index == 0 {
        "point".to_owned()
    } else {
        format!("point{index}")
    };
    let _ = writeln!(kml, "<Folder><name>Landing points{shown}</name>");
    for (sample, [x, y]) in body.points {
        let _ = writeln!(
            kml,
            "<Placemark><name>{sample}</name><styleUrl>#{style}</styleUrl><Point><coordinates>{}</coordinates></Point></Placemark>",
            coordinates(*x, *y)
        );
    }
    let _ = writeln!(kml, "</Folder>");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverted_haversine() {
        let site = Site {
            latitude_deg: 32.990254,
            longitude_deg: -106.974998,
            earth_radius: 6.3781e6,
        };
        // 1 km north is 1000 / R rad of latitude; 1 km east at latitude φ is
        // 1000 / (R cos φ) rad of longitude (to second order in the distance).
        let (lat, lon) = offset_to_lat_lon(&site, 0.0, 1000.0);
        assert!((lat - site.latitude_deg - (1000.0f64 / 6.3781e6).to_degrees()).abs() < 1e-12);
        assert!((lon - site.longitude_deg).abs() < 1e-12);
        let (lat, lon) = offset_to_lat_lon(&site, 1000.0, 0.0);
        let expected = (1000.0 / (6.3781e6 * site.latitude_deg.to_radians().cos())).to_degrees();
        assert!((lon - site.longitude_deg - expected).abs() < 1e-8);
        assert!((lat - site.latitude_deg).abs() < 1e-5);
        assert!(
            lat < site.latitude_deg,
            "a great circle heading due east is at its vertex"
        );
    }

    #[test]
    fn document_is_closed_and_escaped() {
        let site = Site {
            latitude_deg: 0.0,
            longitude_deg: 0.0,
            earth_radius: 6.3781e6,
        };
        let ellipse = Ellipse::fit(&[[0.0, 0.0], [10.0, 5.0], [3.0, -2.0]]).expect("fit");
        let ellipses = [("Landing", ellipse)];
        let body = Body {
            name: None,
            ellipses: &ellipses,
            points: &[(0, [1.0, 2.0])],
            points_total: 5,
        };
        let kml = document("a < b", &site, &[body]);
        assert!(kml.contains("<name>a &lt; b</name>"));
        assert_eq!(kml.matches("<Polygon>").count(), 6);
        assert!(kml.contains("Landing points (first 1 of 5)"));
        assert!(kml.trim_end().ends_with("</kml>"));
        assert!(!kml.contains("point1"));
        // Two bodies: a folder and a point style each, the second's points in its style.
        let bodies = [
            Body {
                name: Some("sustainer"),
                ..body
            },
            Body {
                name: Some("booster & co"),
                ellipses: &[],
                points: &[(3, [-1.0, 0.5])],
                points_total: 1,
            },
        ];
        let kml = document("two", &site, &bodies);
        assert!(kml.contains("<Folder><name>sustainer</name>"));
        assert!(kml.contains("<Folder><name>booster &amp; co</name>"));
        assert!(kml.contains("<Style id=\"point1\">"));
        assert!(kml.contains("<name>3</name><styleUrl>#point1</styleUrl>"));
        assert_eq!(
            kml.matches("<Folder>").count(),
            kml.matches("</Folder>").count()
        );
    }
}
