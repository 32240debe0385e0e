//! The report's tension colour map: RGB (255, 200·F, 0), red at F = 0, yellow at F = 1.
//! Side by side, each rope is drawn in its method's hue instead, tension as its shade
//! ([`hue_shade`]), so that which rope is which method can be seen.

/// The tension at which the colour bar ends (the report's map is yellow from about here on,
/// and a method's hue at its lightest).
pub const SCALE_MAX: f64 = 1.25;

/// The colour of a segment under tension `tension`, clamped to the map's range.
pub fn tension_rgb(tension: f64) -> [u8; 3] {
    let g = (200.0 * tension).clamp(0.0, 255.0);
    [255, g.round() as u8, 0]
}

/// The same, as Rerun's colour.
pub fn tension_colour(tension: f64) -> rerun::Color {
    let [r, g, b] = tension_rgb(tension);
    rerun::Color::from_rgb(r, g, b)
}

/// A method's colour `hue` shaded by `tension`: dark (35 % of the hue) at F = 0, lighter
/// to the hue washed 35 % towards white at F ≥ [`SCALE_MAX`].
pub fn hue_shade(hue: [u8; 3], tension: f64) -> rerun::Color {
    let u = (tension / SCALE_MAX).clamp(0.0, 1.0);
    let [r, g, b] = hue.map(|c| {
        let c = f64::from(c);
        let (dark, light) = (0.35 * c, c + 0.35 * (255.0 - c));
        (dark + (light - dark) * u).round() as u8
    });
    rerun::Color::from_rgb(r, g, b)
}

/// The step of tension a rope side by side is coloured in: 26 shades from red to yellow, a
/// step of 10 in the green channel, which the eye hardly tells from the full map's 255.
pub const SHADE: f64 = 0.05;

/// The rope as few strips as its colours allow: consecutive segments whose tensions round to
/// the same multiple of `shade` share one strip (and one colour). A rope of N segments is N
/// two-point strips in the full map; in shades, its tension (smooth along the string) makes
/// a strip of several segments each, about half the points and a fifth of the colours.
pub fn shaded_strips(
    nodes: &[[f32; 2]],
    tension: &[f64],
    shade: f64,
    colour: impl Fn(f64) -> rerun::Color,
) -> (Vec<Vec<[f32; 2]>>, Vec<rerun::Color>) {
    let mut strips: Vec<Vec<[f32; 2]>> = Vec::new();
    let mut colours = Vec::new();
    let mut current = None;
    for (i, &t) in tension.iter().enumerate() {
        let level = (t / shade).round();
        let (Some(&from), Some(&to)) = (nodes.get(i), nodes.get(i + 1)) else {
            break;
        };
        match strips.last_mut() {
            Some(strip) if current == Some(level) => strip.push(to),
            _ => {
                strips.push(vec![from, to]);
                colours.push(colour(level * shade));
                current = Some(level);
            }
        }
    }
    (strips, colours)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rope_of_one_shade_is_one_strip_through_every_node() {
        let nodes = [[0.0, 0.0], [0.0, 0.5], [0.0, 1.0]];
        let (strips, colours) = shaded_strips(&nodes, &[0.51, 0.49], SHADE, tension_colour);
        assert_eq!(strips, vec![nodes.to_vec()]);
        assert_eq!(colours, vec![tension_colour(0.5)]);
    }

    #[test]
    fn each_change_of_shade_starts_a_strip_at_the_shared_node() {
        let nodes = [[0.0, 0.0], [0.0, 0.25], [0.0, 0.5], [0.0, 0.75], [0.0, 1.0]];
        let (strips, colours) = shaded_strips(&nodes, &[1.0, 1.0, 0.2, 0.0], SHADE, tension_colour);
        assert_eq!(
            strips,
            vec![
                nodes[0..3].to_vec(),
                nodes[2..4].to_vec(),
                nodes[3..5].to_vec()
            ]
        );
        assert_eq!(colours.len(), 3);
        // Every segment is drawn once: the strips' segments add up to the rope's.
        let drawn: usize = strips.iter().map(|s| s.len() - 1).sum();
        assert_eq!(drawn, 4);
    }

    #[test]
    fn a_methods_hue_darkens_at_slack_and_lightens_under_tension_keeping_its_colour() {
        let blue = [40, 80, 220];
        let rgb = |c: rerun::Color| {
            let [r, g, b, _] = c.to_array();
            [r, g, b]
        };
        let (slack, taut) = (rgb(hue_shade(blue, 0.0)), rgb(hue_shade(blue, 2.0)));
        assert_eq!(slack, [14, 28, 77]);
        assert!(taut.iter().zip(slack).all(|(t, s)| *t > s), "{taut:?}");
        // Blue stays the strongest channel at every shade: the hue is kept.
        for f in [0.0, 0.3, 0.6, 1.0, 1.25] {
            let [r, g, b] = rgb(hue_shade(blue, f));
            assert!(b > g && g > r, "F = {f}: {r} {g} {b}");
        }
    }
}
