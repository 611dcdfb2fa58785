//! Where the map's sortie numbers go: at each sortie's first pass, slid along its passes
//! where another number is in the way.

/// A line on the map, in pixels.
pub(super) type PixelLine = Vec<(f64, f64)>;

/// A sortie number's diameter on the map, px, and the step by which a number slides along
/// its pass when another number is in the way.
pub(super) const LABEL_PX: f64 = 18.0;

/// Where each sortie's number goes, given each sortie's passes in pixels in flying order: at
/// the start of its first pass, or, when a number already placed is closer than a label, at
/// the first point further along its passes that is clear (sorties that begin along the same
/// headland would otherwise stack their numbers into one blot), and clear of the marks in
/// `avoid`. When no point is clear, the one farthest from the others.
pub(super) fn label_places<'a>(
    avoid: &[(f64, f64)],
    sorties: impl Iterator<Item = &'a [PixelLine]>,
) -> Vec<(f64, f64)> {
    let mut placed: Vec<(f64, f64)> = avoid.to_vec();
    for passes in sorties {
        let clearance = |point: (f64, f64)| {
            placed
                .iter()
                .map(|other| (point.0 - other.0).hypot(point.1 - other.1))
                .fold(f64::INFINITY, f64::min)
        };
        let candidates: Vec<(f64, f64)> = passes
            .iter()
            .flat_map(|pass| points_along(pass, LABEL_PX))
            .collect();
        let place = candidates
            .iter()
            .copied()
            .find(|&point| clearance(point) >= LABEL_PX)
            .or_else(|| {
                candidates
                    .iter()
                    .copied()
                    .max_by(|a, b| clearance(*a).total_cmp(&clearance(*b)))
            })
            .unwrap_or((0.0, 0.0));
        placed.push(place);
    }
    placed.split_off(avoid.len())
}

/// Points every `step` along a polyline from its start (the start itself first; the
/// polyline's first point alone when it has no length).
fn points_along(line: &[(f64, f64)], step: f64) -> Vec<(f64, f64)> {
    let Some(&start) = line.first() else {
        return Vec::new();
    };
    let mut points = vec![start];
    let mut to_next = step;
    for pair in line.windows(2) {
        let (from, to) = (pair[0], pair[1]);
        let length = (to.0 - from.0).hypot(to.1 - from.1);
        let mut along = to_next;
        while along <= length {
            let share = along / length;
            points.push((
                from.0 + share * (to.0 - from.0),
                from.1 + share * (to.1 - from.1),
            ));
            along += step;
        }
        to_next = along - length;
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_that_would_stack_slide_along_their_passes() {
        // Three sorties starting 5 px apart on the same edge, flying east 100 px.
        let sorties: Vec<Vec<Vec<(f64, f64)>>> = (0..3)
            .map(|row| vec![vec![(0.0, 5.0 * row as f64), (100.0, 5.0 * row as f64)]])
            .collect();
        let places = label_places(&[], sorties.iter().map(Vec::as_slice));
        assert_eq!(places[0], (0.0, 0.0));
        for (index, place) in places.iter().enumerate() {
            for other in &places[..index] {
                assert!((place.0 - other.0).hypot(place.1 - other.1) >= LABEL_PX);
            }
        }
        // A pass shorter than a label: it stays at its start, the best it can do.
        let short = [
            vec![vec![(0.0, 0.0), (5.0, 0.0)]],
            vec![vec![(1.0, 0.0), (4.0, 0.0)]],
        ];
        let places = label_places(&[], short.iter().map(Vec::as_slice));
        assert_eq!(places[1], (1.0, 0.0));
        // A short first pass: the number moves on to the sortie's next pass.
        let sorties = [
            vec![vec![(0.0, 0.0), (0.0, 4.0)]],
            vec![
                vec![(0.0, 2.0), (0.0, 6.0)],
                vec![(0.0, 30.0), (80.0, 30.0)],
            ],
        ];
        let places = label_places(&[], sorties.iter().map(Vec::as_slice));
        assert_eq!(places[1], (0.0, 30.0));
        assert_eq!(
            points_along(&[(0.0, 0.0), (10.0, 0.0), (10.0, 30.0)], 18.0),
            vec![(0.0, 0.0), (10.0, 8.0), (10.0, 26.0)]
        );
    }
}
