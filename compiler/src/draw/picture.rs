//! The picture: the scene drawn at a solution, fitted to the picture, written as SVG
//! (`draw`, the labels merged where points coincide, each element and the traces).

use super::*;

/// Draws `model` at the solution `shown`, with the curves of `options.traces` over `samples`
/// (a sweep's solutions in order, `None` where a solve failed) and, with `options.animate`,
/// the samples played in turn. An error (a traced name that is no point) is in words.
pub fn draw(
    model: &Model,
    shown: &Solution,
    samples: &[Option<Solution>],
    options: &Options,
) -> Result<Drawing, String> {
    if let Some(e) = (options.traces.iter()).find_map(|t| trace_error(model, t)) {
        return Err(e);
    }
    let view = match model.space {
        Space::D2 => View::Xy,
        Space::D3 => options.view,
    };
    let scene = Scene::new(model, shown, view);
    let drawn = Frame::of(shown);
    let geos = |f: &Frame<'_>| -> Vec<Option<Geo>> {
        (scene.elements.iter())
            .map(|e| e.item.geo(f, view))
            .collect()
    };
    let drawn_geos = geos(&drawn);
    let animate = options.animate && samples.len() >= 2;
    let sample_geos: Vec<Option<Vec<Option<Geo>>>> = if animate {
        (samples.iter())
            .map(|s| s.as_ref().map(|s| geos(&Frame::of(s))))
            .collect()
    } else {
        Vec::new()
    };
    // Each traced point's projected position at each sample.
    let traces: Vec<Vec<Option<[f64; 2]>>> = (options.traces.iter())
        .map(|name| {
            (samples.iter())
                .map(|s| {
                    let s = s.as_ref()?;
                    let p = s.points.iter().find(|(n, _)| n == name)?;
                    Some(view.project(&p.1)).filter(|q| q[0].is_finite() && q[1].is_finite())
                })
                .collect()
        })
        .collect();
    let mut extent = Vec::new();
    for g in drawn_geos.iter().flatten() {
        g.extent(&mut extent);
    }
    for g in sample_geos.iter().flatten().flatten().flatten() {
        g.extent(&mut extent);
    }
    extent.extend(traces.iter().flatten().flatten().copied());
    let fit = Fit::around(extent);
    let shapes = |geos: &[Option<Geo>]| -> Vec<Option<Shape>> {
        (scene.elements.iter().zip(geos))
            .map(|(e, g)| g.as_ref().and_then(|g| e.item.shape(g, &fit)))
            .collect()
    };
    let labels = merged_labels(&scene, &shapes(&drawn_geos));
    // Room for the labels: the picture grows where one would cross its edge, in any sample.
    let room = {
        let mut room = [0.0f64; 4];
        let drawn = std::iter::once(&drawn_geos);
        for geos in drawn.chain(sample_geos.iter().flatten()) {
            for (k, shape) in shapes(geos).iter().enumerate() {
                if let (Some(Shape::Text(p, end)), Some(text)) = (shape, labels.get(&k)) {
                    let [x0, y0, x1, y1] = label_box(*p, *end, text);
                    let pad = LABEL_PAD;
                    room[0] = room[0].max(pad - x0);
                    room[1] = room[1].max(pad - y0);
                    room[2] = room[2].max(x1 + pad - fit.size[0]);
                    room[3] = room[3].max(y1 + pad - fit.size[1]);
                }
            }
        }
        room
    };
    let fit = fit.grow(room);
    let shapes = |geos: &[Option<Geo>]| -> Vec<Option<Shape>> {
        (scene.elements.iter().zip(geos))
            .map(|(e, g)| g.as_ref().and_then(|g| e.item.shape(g, &fit)))
            .collect()
    };
    let drawn_shapes = shapes(&drawn_geos);
    let sample_shapes: Vec<Option<Vec<Option<Shape>>>> = (sample_geos.iter())
        .map(|g| g.as_ref().map(|g| shapes(g)))
        .collect();
    let mut out = String::new();
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" \
         width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">",
        w = svg::num(fit.size[0]),
        h = svg::num(fit.size[1]),
    );
    let title = model.source.name().rsplit(['/', '\\']).next().unwrap_or("");
    let _ = writeln!(out, "<title>{}</title>", svg::escape(title));
    out.push_str(&svg::style());
    out.push_str(&svg::defs());
    out.push_str("<rect class=\"background\" width=\"100%\" height=\"100%\"/>\n");
    let dur = format!(
        "{}s",
        svg::num(SECONDS_A_SAMPLE * sample_shapes.len() as f64)
    );
    for layer in Layer::ALL {
        if layer == Layer::Traces {
            write_traces(&mut out, &options.traces, &traces, &fit);
            continue;
        }
        let mut body = String::new();
        for (k, e) in scene.elements.iter().enumerate() {
            if e.layer != layer {
                continue;
            }
            let Some(shape) = &drawn_shapes[k] else {
                continue;
            };
            let text = match &e.item {
                Item::Label { .. } => match labels.get(&k) {
                    Some(text) => Some(text.as_str()),
                    None => continue,
                },
                _ => None,
            };
            // Each sample's attributes, a failed one repeating the last that solved.
            let mut frames = Vec::new();
            if animate {
                let mut last = shape.attributes();
                for s in &sample_shapes {
                    if let Some(Some(shape)) = s.as_ref().map(|s| &s[k]) {
                        last = shape.attributes();
                    }
                    frames.push(last.clone());
                }
            }
            write_element(&mut body, e, shape, text, &frames, &dur);
        }
        if !body.is_empty() {
            let _ = writeln!(out, "<g id=\"{}\">", layer.name());
            out.push_str(&body);
            out.push_str("</g>\n");
        }
    }
    out.push_str("</svg>\n");
    Ok(Drawing {
        svg: out,
        view,
        fit,
    })
}

/// A cell of a one-pixel grid.
type Cell = (i64, i64);

/// The labels drawn, by element index, with their text: the labels of points that coincide
/// in the drawn solution (within half a pixel of the group's first) are one, at the first, their names joined in model
/// order; other labels are their element's name.
fn merged_labels(scene: &Scene, shapes: &[Option<Shape>]) -> HashMap<usize, String> {
    let mut out: HashMap<usize, String> = HashMap::new();
    // The first label of each group, with its pixel, by the pixel's cell.
    let mut first_at: HashMap<Cell, Vec<(usize, [f64; 2])>> = HashMap::new();
    for (k, e) in scene.elements.iter().enumerate() {
        let (Item::Label { at }, Some(Shape::Text(p, _))) = (&e.item, &shapes[k]) else {
            continue;
        };
        if !matches!(at, At::Point(_)) {
            out.insert(k, e.name.clone());
            continue;
        }
        // Within half a pixel: in the label's cell of a one-pixel grid or a neighbour's.
        let cell = (p[0].floor() as i64, p[1].floor() as i64);
        let near = (-1..=1)
            .flat_map(|i| (-1..=1).map(move |j| (cell.0 + i, cell.1 + j)))
            .filter_map(|c| first_at.get(&c))
            .flatten()
            .find(|&&(_, q)| (p[0] - q[0]).abs() <= 0.5 && (p[1] - q[1]).abs() <= 0.5)
            .map(|&(first, _)| first);
        match near {
            Some(first) => {
                if let Some(text) = out.get_mut(&first) {
                    text.push_str(", ");
                    text.push_str(&e.name);
                }
            }
            None => {
                first_at.entry(cell).or_default().push((k, *p));
                out.insert(k, e.name.clone());
            }
        }
    }
    out
}

/// Writes one element: its tag, classes, name and position attributes, and with `frames` (one
/// list of attributes a sample) an `<animate>` for each attribute that changes.
fn write_element(
    out: &mut String,
    e: &Element,
    shape: &Shape,
    text: Option<&str>,
    frames: &[Vec<(&'static str, String)>],
    dur: &str,
) {
    let attributes = shape.attributes();
    let _ = write!(
        out,
        "  <{} class=\"{}\" data-name=\"{}\"",
        shape.tag(),
        e.class,
        svg::escape(&e.name)
    );
    match shape {
        Shape::Use(_) => out.push_str(" xlink:href=\"#ground-symbol\""),
        Shape::Text(_, true) => out.push_str(" text-anchor=\"end\""),
        _ => {}
    }
    for (a, v) in &attributes {
        let _ = write!(out, " {a}=\"{v}\"");
    }
    if let Some(m) = e.marker {
        let _ = write!(out, " marker-end=\"url(#{m})\"");
    }
    let mut children = String::new();
    for (i, (a, _)) in attributes.iter().enumerate() {
        let values: Vec<&str> = (frames.iter())
            .filter_map(|f| f.get(i).map(|(_, v)| v.as_str()))
            .collect();
        if values.len() >= 2 && values.iter().any(|v| *v != values[0]) {
            let _ = writeln!(
                children,
                "    <animate attributeName=\"{a}\" dur=\"{dur}\" repeatCount=\"indefinite\" \
                 values=\"{}\"/>",
                values.join(";")
            );
        }
    }
    match (text, children.is_empty()) {
        (None, true) => out.push_str("/>\n"),
        (None, false) => {
            let _ = write!(out, ">\n{children}  </{}>\n", shape.tag());
        }
        (Some(t), true) => {
            let _ = writeln!(out, ">{}</text>", svg::escape(t));
        }
        (Some(t), false) => {
            let _ = write!(out, ">{}\n{children}  </text>\n", svg::escape(t));
        }
    }
}

/// The `traces` group: for each traced point, a group of its runs (polylines, or a dot for a
/// run of one sample).
fn write_traces(out: &mut String, names: &[String], traces: &[Vec<Option<[f64; 2]>>], fit: &Fit) {
    if names.is_empty() {
        return;
    }
    out.push_str("<g id=\"traces\">\n");
    for (k, (name, samples)) in names.iter().zip(traces).enumerate() {
        let colour = k % svg::TRACE_COLOURS.len();
        let _ = writeln!(
            out,
            "  <g class=\"trace t{colour}\" data-name=\"{}\">",
            svg::escape(name)
        );
        for run in runs(samples) {
            let px: Vec<[f64; 2]> = run.iter().map(|p| fit.pixel(*p)).collect();
            if let [p] = px[..] {
                let _ = writeln!(
                    out,
                    "    <circle class=\"trace-point t{colour}\" cx=\"{}\" cy=\"{}\" r=\"2\"/>",
                    svg::num(p[0]),
                    svg::num(p[1])
                );
            } else {
                let _ = writeln!(out, "    <polyline points=\"{}\"/>", svg::points(&px));
            }
        }
        out.push_str("  </g>\n");
    }
    out.push_str("</g>\n");
}
