//! The report's tension colour map: RGB (255, 200·F, 0), red at F = 0, yellow at F = 1.

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
