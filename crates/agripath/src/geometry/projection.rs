//! WGS84 longitude/latitude ⇄ UTM metres (transverse Mercator, Krüger series to n⁶).
//!
//! Formulas: C. F. F. Karney, "Transverse Mercator with an accuracy of a few nanometres",
//! J. Geodesy 85 (2011) (Karney 2011, docs/references.md), eqs. (7)-(11) and (35)-(36) with the 6th-order coefficients of its
//! appendix. Within a UTM zone the series is accurate to far below a millimetre, which the tests
//! check against PROJ (pyproj) figures. Pure Rust, no tables: see `docs/decisions/0002-projection.md`.

/// WGS84 semi-major axis, metres.
const SEMI_MAJOR_AXIS_M: f64 = 6_378_137.0;
/// WGS84 flattening.
const FLATTENING: f64 = 1.0 / 298.257_223_563;
/// UTM central scale factor.
const SCALE_FACTOR: f64 = 0.9996;
const FALSE_EASTING_M: f64 = 500_000.0;
const FALSE_NORTHING_SOUTH_M: f64 = 10_000_000.0;

/// A UTM zone: number 1..=60 and hemisphere.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UtmZone {
    /// Zone number, 1..=60.
    pub number: u8,
    /// True in the southern hemisphere (false northing 10,000 km).
    pub south: bool,
}

impl UtmZone {
    /// The standard zone of a longitude/latitude (without the Norway/Svalbard exceptions,
    /// which only change the zone number, not the accuracy for a farm).
    pub fn containing(lon_deg: f64, lat_deg: f64) -> Self {
        let wrapped = (lon_deg + 180.0).rem_euclid(360.0);
        let number = ((wrapped / 6.0).floor() as u8 % 60) + 1;
        Self {
            number,
            south: lat_deg < 0.0,
        }
    }

    /// EPSG code of this zone on WGS84 (326zz north, 327zz south).
    pub fn epsg(self) -> u32 {
        if self.south {
            32700 + u32::from(self.number)
        } else {
            32600 + u32::from(self.number)
        }
    }

    fn central_meridian_rad(self) -> f64 {
        (f64::from(self.number) * 6.0 - 183.0).to_radians()
    }

    fn false_northing_m(self) -> f64 {
        if self.south {
            FALSE_NORTHING_SOUTH_M
        } else {
            0.0
        }
    }
}

struct Series {
    rectifying_radius_m: f64,
    alpha: [f64; 6],
    beta: [f64; 6],
    delta: [f64; 6],
    eccentricity_term: f64,
}

fn series() -> Series {
    let n = FLATTENING / (2.0 - FLATTENING);
    let n2 = n * n;
    let n3 = n2 * n;
    let n4 = n3 * n;
    let n5 = n4 * n;
    let n6 = n5 * n;
    Series {
        rectifying_radius_m: SEMI_MAJOR_AXIS_M / (1.0 + n)
            * (1.0 + n2 / 4.0 + n4 / 64.0 + n6 / 256.0),
        alpha: [
            n / 2.0 - 2.0 * n2 / 3.0 + 5.0 * n3 / 16.0 + 41.0 * n4 / 180.0 - 127.0 * n5 / 288.0
                + 7891.0 * n6 / 37800.0,
            13.0 * n2 / 48.0 - 3.0 * n3 / 5.0 + 557.0 * n4 / 1440.0 + 281.0 * n5 / 630.0
                - 1983433.0 * n6 / 1935360.0,
            61.0 * n3 / 240.0 - 103.0 * n4 / 140.0
                + 15061.0 * n5 / 26880.0
                + 167603.0 * n6 / 181440.0,
            49561.0 * n4 / 161280.0 - 179.0 * n5 / 168.0 + 6601661.0 * n6 / 7257600.0,
            34729.0 * n5 / 80640.0 - 3418889.0 * n6 / 1995840.0,
            212378941.0 * n6 / 319334400.0,
        ],
        beta: [
            n / 2.0 - 2.0 * n2 / 3.0 + 37.0 * n3 / 96.0 - n4 / 360.0 - 81.0 * n5 / 512.0
                + 96199.0 * n6 / 604800.0,
            n2 / 48.0 + n3 / 15.0 - 437.0 * n4 / 1440.0 + 46.0 * n5 / 105.0
                - 1118711.0 * n6 / 3870720.0,
            17.0 * n3 / 480.0 - 37.0 * n4 / 840.0 - 209.0 * n5 / 4480.0 + 5569.0 * n6 / 90720.0,
            4397.0 * n4 / 161280.0 - 11.0 * n5 / 504.0 - 830251.0 * n6 / 7257600.0,
            4583.0 * n5 / 161280.0 - 108847.0 * n6 / 3991680.0,
            20648693.0 * n6 / 638668800.0,
        ],
        delta: [
            2.0 * n - 2.0 * n2 / 3.0 - 2.0 * n3 + 116.0 * n4 / 45.0 + 26.0 * n5 / 45.0
                - 2854.0 * n6 / 675.0,
            7.0 * n2 / 3.0 - 8.0 * n3 / 5.0 - 227.0 * n4 / 45.0
                + 2704.0 * n5 / 315.0
                + 2323.0 * n6 / 945.0,
            56.0 * n3 / 15.0 - 136.0 * n4 / 35.0 - 1262.0 * n5 / 105.0 + 73814.0 * n6 / 2835.0,
            4279.0 * n4 / 630.0 - 332.0 * n5 / 35.0 - 399572.0 * n6 / 14175.0,
            4174.0 * n5 / 315.0 - 144838.0 * n6 / 6237.0,
            601676.0 * n6 / 22275.0,
        ],
        eccentricity_term: 2.0 * n.sqrt() / (1.0 + n),
    }
}

/// Longitude/latitude in degrees to (easting, northing) in metres in `zone`.
pub fn to_utm(lon_deg: f64, lat_deg: f64, zone: UtmZone) -> (f64, f64) {
    let s = series();
    let latitude = lat_deg.to_radians();
    let longitude = lon_deg.to_radians() - zone.central_meridian_rad();
    // Conformal latitude (Karney eq. 7-9), through t = tan χ.
    let sin_lat = latitude.sin();
    let t =
        (sin_lat.atanh() - s.eccentricity_term * (s.eccentricity_term * sin_lat).atanh()).sinh();
    let xi_prime = t.atan2(longitude.cos());
    let eta_prime = (longitude.sin() / (1.0 + t * t).sqrt()).atanh();
    let mut xi = xi_prime;
    let mut eta = eta_prime;
    for (index, alpha) in s.alpha.iter().enumerate() {
        let order = 2.0 * (index as f64 + 1.0);
        xi += alpha * (order * xi_prime).sin() * (order * eta_prime).cosh();
        eta += alpha * (order * xi_prime).cos() * (order * eta_prime).sinh();
    }
    let scale = SCALE_FACTOR * s.rectifying_radius_m;
    (
        FALSE_EASTING_M + scale * eta,
        zone.false_northing_m() + scale * xi,
    )
}

/// (easting, northing) in metres in `zone` back to longitude/latitude in degrees.
pub fn from_utm(easting_m: f64, northing_m: f64, zone: UtmZone) -> (f64, f64) {
    let s = series();
    let scale = SCALE_FACTOR * s.rectifying_radius_m;
    let xi = (northing_m - zone.false_northing_m()) / scale;
    let eta = (easting_m - FALSE_EASTING_M) / scale;
    let mut xi_prime = xi;
    let mut eta_prime = eta;
    for (index, beta) in s.beta.iter().enumerate() {
        let order = 2.0 * (index as f64 + 1.0);
        xi_prime -= beta * (order * xi).sin() * (order * eta).cosh();
        eta_prime -= beta * (order * xi).cos() * (order * eta).sinh();
    }
    let conformal_latitude = (xi_prime.sin() / eta_prime.cosh()).asin();
    let longitude = eta_prime.sinh().atan2(xi_prime.cos());
    let mut latitude = conformal_latitude;
    for (index, delta) in s.delta.iter().enumerate() {
        let order = 2.0 * (index as f64 + 1.0);
        latitude += delta * (order * conformal_latitude).sin();
    }
    (
        wrap_longitude((longitude + zone.central_meridian_rad()).to_degrees()),
        latitude.to_degrees(),
    )
}

/// A longitude in degrees brought into [−180, 180): zone 60's central meridian plus 4° is
/// −179°, not 181°.
pub fn wrap_longitude(lon_deg: f64) -> f64 {
    // In range already: returned as it is, not re-rounded through the sum.
    if (-180.0..180.0).contains(&lon_deg) {
        lon_deg
    } else {
        (lon_deg + 180.0).rem_euclid(360.0) - 180.0
    }
}

/// The mean of longitudes on the circle, in [−180, 180): the mean of 179.9° and −179.9° is
/// 180°, not 0°.
pub fn mean_longitude(longitudes_deg: impl IntoIterator<Item = f64>) -> f64 {
    let (sine, cosine) = longitudes_deg
        .into_iter()
        .fold((0.0, 0.0), |(sine, cosine), lon: f64| {
            let radians = lon.to_radians();
            (sine + radians.sin(), cosine + radians.cos())
        });
    wrap_longitude(sine.atan2(cosine).to_degrees())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// PROJ 9 (pyproj) figure quoted in the ecosystem study: 47.3977419 N, 8.545594 E in 32N.
    #[test]
    fn matches_proj_in_zurich() {
        let zone = UtmZone::containing(8.545594, 47.3977419);
        assert_eq!(
            zone,
            UtmZone {
                number: 32,
                south: false
            }
        );
        let (easting, northing) = to_utm(8.545594, 47.3977419, zone);
        assert!((easting - 465_710.758_5).abs() < 1e-3, "{easting}");
        assert!((northing - 5_249_465.352_7).abs() < 1e-3, "{northing}");
    }

    #[test]
    fn round_trips_to_a_tenth_of_a_millimetre_across_a_zone() {
        for lat in [-79.5, -45.0, -10.2, 0.0, 0.3, 23.4, 52.1, 83.9] {
            for offset in [-2.9, -1.0, 0.0, 1.7, 2.95] {
                let lon = 117.0 + offset;
                let zone = UtmZone::containing(117.0, lat);
                let (easting, northing) = to_utm(lon, lat, zone);
                let (lon_back, lat_back) = from_utm(easting, northing, zone);
                // 1e-9 degrees is about 0.1 mm.
                assert!((lon_back - lon).abs() < 1e-9, "lon {lon} {lat}: {lon_back}");
                assert!((lat_back - lat).abs() < 1e-9, "lat {lon} {lat}: {lat_back}");
            }
        }
    }

    #[test]
    fn longitudes_wrap_across_the_antimeridian() {
        assert!((mean_longitude([179.999, -179.999]).abs() - 180.0).abs() < 1e-9);
        assert!((mean_longitude([10.0, 20.0]) - 15.0).abs() < 1e-9);
        assert_eq!(wrap_longitude(181.0), -179.0);
        // A point 3° east of zone 60's central meridian (177°E) comes back as 180° ± 0.
        let zone = UtmZone::containing(179.0, -16.0);
        assert_eq!(zone.number, 60);
        let (easting, northing) = to_utm(-179.5, -16.0, zone);
        let (lon, lat) = from_utm(easting, northing, zone);
        assert!(
            (lon + 179.5).abs() < 1e-9 && (lat + 16.0).abs() < 1e-9,
            "{lon} {lat}"
        );
    }

    #[test]
    fn zone_numbers_and_epsg() {
        assert_eq!(UtmZone::containing(-180.0, 10.0).number, 1);
        assert_eq!(UtmZone::containing(179.99, 10.0).number, 60);
        assert_eq!(UtmZone::containing(105.6, -10.5).epsg(), 32748);
    }
}
