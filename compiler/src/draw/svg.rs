//! SVG text, written by hand: numbers at a fixed precision, escaped text, the one `<style>`
//! block and the shared definitions (hatching, arrowheads, the ground symbol).

use std::fmt::Write as _;

/// Decimals of every coordinate written: a thousandth of a pixel.
pub const DECIMALS: usize = 3;

/// A number as written in the SVG: rounded to [`DECIMALS`] decimals, trailing zeros and a
/// trailing point dropped, never `-0`. A non-finite number (which the drawing never writes: it
/// leaves out what has no finite position) is written `0`, so that the file stays valid.
pub fn num(x: f64) -> String {
    if !x.is_finite() {
        return "0".to_string();
    }
    let mut s = format!("{x:.DECIMALS$}");
    if s.contains('.') {
        let kept = s.trim_end_matches('0').trim_end_matches('.').len();
        s.truncate(kept);
    }
    if s == "-0" {
        s = "0".to_string();
    }
    s
}

/// A pixel as `x,y`.
pub fn pair(p: [f64; 2]) -> String {
    format!("{},{}", num(p[0]), num(p[1]))
}

/// A list of pixels as the `points` of a polyline or polygon.
pub fn points(ps: &[[f64; 2]]) -> String {
    ps.iter().map(|p| pair(*p)).collect::<Vec<_>>().join(" ")
}

/// Text escaped for XML content and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            _ => out.push(c),
        }
    }
    out
}

/// Colours of bodies, in model order, cycled (class `b0`, `b1`, ...).
pub const BODY_COLOURS: [&str; 6] = [
    "#4e79a7", "#f28e2b", "#59a14f", "#b07aa1", "#76b7b2", "#edc948",
];

/// Colours of traced curves, in the order of `--trace` (class `t0`, `t1`, ...).
pub const TRACE_COLOURS: [&str; 4] = ["#d62728", "#9467bd", "#8c564b", "#17becf"];

/// The fill of a point's dot: what a render shows at a solved point's pixel.
pub const POINT_COLOUR: &str = "#1b1b1b";

/// The radius of a point's dot, in pixels.
pub const POINT_RADIUS: f64 = 4.0;

/// The radius of a segment's end's or a circle's centre's dot, in pixels.
pub const END_RADIUS: f64 = 2.5;

/// The drawing's style sheet, the one `<style>` element: every class the drawing uses.
pub fn style() -> String {
    let mut s = String::from("<style>\n");
    let rules: &[(&str, String)] = &[
        (".background", "fill: #ffffff".into()),
        (
            ".plane",
            "fill: #9ecae1; fill-opacity: 0.18; stroke: #6baed6; stroke-width: 1".into(),
        ),
        (
            ".segment, .circle, .line",
            "fill: none; stroke: #333333; stroke-width: 1.5".into(),
        ),
        (".line", "stroke-dasharray: 8 4 2 4".into()),
        (
            ".link",
            "fill: none; stroke: #666666; stroke-width: 2.5; stroke-linecap: round".into(),
        ),
        (
            ".body",
            "fill-opacity: 0.25; stroke-width: 2; stroke-linejoin: round".into(),
        ),
        (
            ".bar",
            "stroke-width: 9; stroke-linecap: round; stroke-opacity: 0.6".into(),
        ),
        (".fixed", "fill: url(#hatch); stroke: #444444".into()),
        (".bar.fixed", "stroke-opacity: 0.35".into()),
        (
            ".segment.fixed, .circle.fixed, .line.fixed",
            "fill: none; stroke: #000000; stroke-width: 2.5".into(),
        ),
        (
            ".trace",
            "fill: none; stroke-width: 1.5; stroke-linejoin: round".into(),
        ),
        (".axis, .vector", "stroke-width: 1.5; fill: none".into()),
        (".axis.x", "stroke: #c0392b".into()),
        (".axis.z", "stroke: #2c7fb8".into()),
        (".vector", "stroke: #555555".into()),
        (
            ".ground",
            "fill: url(#hatch); stroke: #444444; stroke-width: 1".into(),
        ),
        (".point", format!("fill: {POINT_COLOUR}")),
        (".end", format!("fill: {POINT_COLOUR}")),
        (
            ".label",
            "font-family: sans-serif; font-size: 12px; fill: #1b1b1b; stroke: #ffffff; \
             stroke-width: 3; paint-order: stroke; stroke-linejoin: round"
                .into(),
        ),
    ];
    for (selector, body) in rules {
        let _ = writeln!(s, "  {selector} {{ {body} }}");
    }
    for (k, c) in BODY_COLOURS.iter().enumerate() {
        let _ = writeln!(s, "  .b{k} {{ fill: {c}; stroke: {c} }}");
    }
    for (k, c) in TRACE_COLOURS.iter().enumerate() {
        let _ = writeln!(s, "  .t{k} {{ stroke: {c} }}");
        let _ = writeln!(s, "  .trace-point.t{k} {{ fill: {c}; stroke: none }}");
    }
    s.push_str("</style>\n");
    s
}

/// The shared definitions: the hatching of fixed geoms, the arrowheads of axes and vectors (one
/// per colour), and the ground symbol drawn under a fixed point.
pub fn defs() -> String {
    let mut s = String::from("<defs>\n");
    s.push_str(
        "  <pattern id=\"hatch\" width=\"5\" height=\"5\" patternUnits=\"userSpaceOnUse\" \
         patternTransform=\"rotate(45)\"><rect width=\"5\" height=\"5\" fill=\"#ffffff\"/>\
         <line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"5\" stroke=\"#444444\" stroke-width=\"1.5\"/>\
         </pattern>\n",
    );
    for (id, colour) in [
        ("arrow-x", "#c0392b"),
        ("arrow-z", "#2c7fb8"),
        ("arrow", "#555555"),
    ] {
        let _ = writeln!(
            s,
            "  <marker id=\"{id}\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" markerWidth=\"7\" \
             markerHeight=\"7\" markerUnits=\"userSpaceOnUse\" orient=\"auto\">\
             <path d=\"M0,1 L10,5 L0,9 z\" fill=\"{colour}\"/></marker>"
        );
    }
    s.push_str(
        "  <g id=\"ground-symbol\"><path class=\"ground\" d=\"M0,0 L-7,11 L7,11 z\"/>\
         <rect class=\"ground\" x=\"-11\" y=\"11\" width=\"22\" height=\"5\"/></g>\n",
    );
    s.push_str("</defs>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_have_three_decimals_at_most_and_no_negative_zero() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(12.5), "12.5");
        assert_eq!(num(-1.23456), "-1.235");
        assert_eq!(num(0.0005), "0.001");
        assert_eq!(num(0.0004), "0");
        assert_eq!(num(-0.0004), "0");
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(100.0), "100");
        assert_eq!(num(1234.5678), "1234.568");
        assert_eq!(num(f64::NAN), "0");
        assert_eq!(num(f64::INFINITY), "0");
        assert_eq!(pair([1.25, -0.5]), "1.25,-0.5");
        assert_eq!(points(&[[0.0, 1.0], [2.0, 3.0]]), "0,1 2,3");
    }

    #[test]
    fn text_is_escaped() {
        assert_eq!(escape("a<b & \"c\"'"), "a&lt;b &amp; &quot;c&quot;&apos;");
        assert_eq!(escape("crank.b"), "crank.b");
    }

    #[test]
    fn the_style_sheet_names_every_colour_class() {
        let s = style();
        for k in 0..BODY_COLOURS.len() {
            assert!(s.contains(&format!(".b{k} ")), "{s}");
        }
        for k in 0..TRACE_COLOURS.len() {
            assert!(s.contains(&format!(".t{k} ")), "{s}");
        }
        assert!(s.starts_with("<style>") && s.ends_with("</style>\n"));
    }
}
