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

/// A field's label, where it would go (pixels) and the field's size in pixels.
pub(super) type Labelled = (String, (f64, f64), (f64, f64));

/// How a field's name is written on the map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum FieldLabel {
    /// Across, centred at the point.
    Across(f64, f64),
    /// Up the field (rotated a quarter turn), centred at the point: the name is wider than
    /// its field, which is taller than wide (terraces, strips).
    Up(f64, f64),
}

impl FieldLabel {
    /// Its SVG `transform`.
    pub(super) fn transform(&self) -> String {
        match self {
            Self::Across(x, y) => format!("translate({x:.2} {y:.2})"),
            Self::Up(x, y) => format!("translate({x:.2} {y:.2}) rotate(-90)"),
        }
    }
}

/// A map label's font size, px, and the width of one of its characters, about.
const FIELD_LABEL_PX: f64 = 13.0;
const CHARACTER_PX: f64 = 8.0;

/// Where each field's label goes: at its inner point (pixels), the field's pixel size
/// beside it; up the field where the name is wider than the field and the field taller
/// than wide; a label across that would overlap one already placed moves down a line at a
/// time (at most five) until it is clear (ten terraces' names printed over each other on
/// one row: the eleventh trial).
pub(super) fn field_label_places(fields: &[Labelled]) -> Vec<FieldLabel> {
    let mut boxes: Vec<[f64; 4]> = Vec::new();
    let overlaps =
        |a: &[f64; 4], b: &[f64; 4]| a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
    fields
        .iter()
        .map(|(text, (x, y), (width_px, height_px))| {
            let (x, y, width_px, height_px) = (*x, *y, *width_px, *height_px);
            let text_px = CHARACTER_PX * text.chars().count() as f64;
            if text_px > width_px && height_px > width_px {
                let half = text_px / 2.0;
                boxes.push([
                    x - FIELD_LABEL_PX / 2.0,
                    y - half,
                    x + FIELD_LABEL_PX / 2.0,
                    y + half,
                ]);
                return FieldLabel::Up(x, y);
            }
            let at = |y: f64| {
                [
                    x - text_px / 2.0,
                    y - FIELD_LABEL_PX,
                    x + text_px / 2.0,
                    y + 3.0,
                ]
            };
            let mut placed_y = y;
            for step in 0..6 {
                placed_y = y + step as f64 * (FIELD_LABEL_PX + 3.0);
                if !boxes.iter().any(|other| overlaps(&at(placed_y), other)) {
                    break;
                }
            }
            boxes.push(at(placed_y));
            FieldLabel::Across(x, placed_y)
        })
        .collect()
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

    #[test]
    fn names_wider_than_narrow_tall_fields_run_up_them_and_others_step_clear() {
        // Two terraces 40 px wide and 600 tall, side by side; two wide fields whose names
        // would print over each other on one row.
        let name = |characters: usize| "n".repeat(characters);
        let places = field_label_places(&[
            (name(14), (20.0, 300.0), (40.0, 600.0)),
            (name(14), (60.0, 300.0), (40.0, 600.0)),
            (name(20), (500.0, 100.0), (300.0, 200.0)),
            (name(20), (560.0, 100.0), (300.0, 200.0)),
        ]);
        assert_eq!(places[0], FieldLabel::Up(20.0, 300.0));
        assert_eq!(places[1], FieldLabel::Up(60.0, 300.0));
        assert_eq!(places[2], FieldLabel::Across(500.0, 100.0));
        assert_eq!(places[3], FieldLabel::Across(560.0, 116.0));
    }
}
