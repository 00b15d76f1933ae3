//! `godel plot geodesics` for the Gödel-type family of Rebouças and Tiomno (docs/physics.md,
//! "The Gödel-type family"): the future-directed light rays from the origin in the plane
//! z = 0 of one member, or of up to three members side by side (`--members`, values of
//! m²/Ω² at one vorticity Ω), in x = ρ cos φ, y = ρ sin φ with ρ the proper radius, in units
//! of 1/Ω.
//!
//! Where m² < 4Ω² the circles about the axis are closed timelike curves beyond ρ_c,
//! tanh(mρ_c/2) = m/(2Ω) (ρ_c = 1/Ω for m² = 0, tan(μρ_c/2) = μ/(2Ω) for m² = −μ²), and the
//! in-plane rays from the origin turn exactly there: with E = −p_t and p_φ = 0,
//! (dρ/dλ)² = E²(1 − H²/D²), which vanishes where H = D, i.e. at ρ_c. There they come back
//! to the origin, after at most 2ρ_c of coordinate time (dt/dρ = √(1 − H²/D²) ≤ 1), so the
//! traces stop at the axis return with the bound 2ρ_c. Where m² ≥ 4Ω² the member is causal,
//! H/D = (2Ω/m) tanh(mρ/2) < 1 everywhere, and the rays escape: each is traced until the
//! coordinate time t(ρ) = ∫₀^ρ √(1 − H²/D²) dρ' at which it is beyond the frame's corner,
//! or at most at mρ = [`ESCAPE_M_RHO`]. For m² < 0 the coordinates end at ρ = π/μ, drawn
//! where it lies within the frame.
//!
//! The rays are traced numerically (`plot::kit::trace_ray_within`).

use crate::plot::kit::{arrowhead, caption, tick_label, trace_ray_within, Frame, Legend, PALETTE};
use crate::plot::svg::{f, Svg, Weight};
use spacetime::{GodelType, Metric, TraceLimits};
use std::f64::consts::PI;

/// The frame shows this many ρ_c of the widest member with a ρ_c (in units of 1/Ω)…
const MARGIN: f64 = 1.25;
/// …or this half-width where no member has one.
const CAUSAL_HALF: f64 = 2.0;
/// Escaping rays are traced to this many half-widths (beyond the corner, √2).
const EXIT: f64 = 1.45;
/// Escaping rays are traced at most to this mρ: beyond mρ ≈ 14 the metric's terms, of the
/// order of e^{2mρ}, cancel to too few digits for the integrator's tolerance (seen: the
/// step budget of 100000 spent there for m² = 4.5Ω² and 100Ω², Ω = 1).
pub const ESCAPE_M_RHO: f64 = 12.0;
/// Tint of the region of closed timelike curves.
const CTC_TINT: &str = "#FBE3E3";
/// Grey beyond the coordinates' end (m² < 0).
const BEYOND_TINT: &str = "#DDDDDD";

/// The rays of one member, in units of 1/Ω.
pub struct MemberRays {
    pub member: GodelType,
    /// Per ray: its points (x, y)·Ω.
    rays: Vec<Vec<(f64, f64)>>,
    /// The return time to the origin (mean over the rays), in units of 1/Ω; None where the
    /// rays escape.
    return_time: Option<f64>,
    /// Where escaping rays were stopped at mρ = [`ESCAPE_M_RHO`] before the frame's
    /// corner: that ρ, in units of 1/Ω.
    cut: Option<f64>,
}

/// Half-width of the frame that shows every member's ρ_c, in units of 1/Ω.
pub fn frame_half(members: &[GodelType]) -> f64 {
    members
        .iter()
        .filter_map(|g| g.critical_radius().map(|r| MARGIN * r * g.omega))
        .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))))
        .unwrap_or(CAUSAL_HALF)
}

/// Coordinate time at which an in-plane ray from the axis of a causal member (m² ≥ 4Ω²)
/// reaches ρ: ∫₀^ρ √(1 − (2Ω/m)² tanh²(mρ'/2)) dρ' (Simpson's rule; the integrand is smooth).
fn escape_time(member: GodelType, rho: f64) -> f64 {
    let m = member.m2.sqrt();
    let k = 2.0 * member.omega / m;
    let g = |r: f64| (1.0 - (k * (0.5 * m * r).tanh()).powi(2)).max(0.0).sqrt();
    let n = 2000;
    let h = rho / n as f64;
    let mut sum = g(0.0) + g(rho);
    for i in 1..n {
        sum += g(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

/// Traces `n` in-plane rays from the origin of `member` (evenly spaced azimuths), for a frame
/// of half-width `half` (units of 1/Ω).
pub fn trace_member(member: GodelType, n: usize, half: f64) -> anyhow::Result<MemberRays> {
    let metric = Metric::GodelType(member);
    let mut cut = None;
    let limits = match member.critical_radius() {
        // T ≤ 2ρ_c (module documentation); the axis return stops it.
        Some(rho_c) => TraceLimits {
            until_time: Some(2.0 * rho_c * (1.0 + 1e-3)),
            stop_at_axis_return: true,
            ..Default::default()
        },
        None => {
            let corner = EXIT * half / member.omega;
            let bound = ESCAPE_M_RHO / member.m2.sqrt();
            if bound < corner {
                cut = Some(bound * member.omega);
            }
            TraceLimits {
                until_time: Some(escape_time(member, corner.min(bound))),
                ..Default::default()
            }
        }
    };
    let mut rays = Vec::with_capacity(n);
    let mut times = Vec::with_capacity(n);
    for k in 0..n {
        let chi = 2.0 * PI * k as f64 / n as f64;
        let (events, t_end) = trace_ray_within(metric, [chi.cos(), chi.sin(), 0.0], &limits)?;
        let w = member.omega;
        rays.push(events.iter().map(|e| (e.x * w, e.y * w)).collect());
        times.push(t_end * w);
    }
    let return_time = member
        .critical_radius()
        .map(|_| times.iter().sum::<f64>() / n.max(1) as f64);
    Ok(MemberRays {
        member,
        rays,
        return_time,
        cut,
    })
}

/// m²/Ω² written as a multiple of Ω²: "0", "2Ω²", "−Ω²", "4.5Ω²".
fn m2_text(member: GodelType) -> String {
    let ratio = member.m2 / (member.omega * member.omega);
    let number = tick_label(ratio);
    match number.as_str() {
        "0" => "0".to_string(),
        "1" => "Ω²".to_string(),
        "−1" => "−Ω²".to_string(),
        _ => format!("{number}Ω²"),
    }
}

/// What a member is called in the labels.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// m² = 0.
    SomRaychaudhuri,
    /// m² = 2Ω².
    Godel,
    /// m² ≥ 4Ω².
    Causal,
    /// Any other: closed timelike curves beyond ρ_c.
    Acausal,
}

impl Kind {
    fn of(member: GodelType) -> Kind {
        let ratio = member.m2 / (member.omega * member.omega);
        if member.m2 == 0.0 {
            Kind::SomRaychaudhuri
        } else if (ratio - 2.0).abs() < 1e-12 {
            Kind::Godel
        } else if member.critical_radius().is_none() {
            Kind::Causal
        } else {
            Kind::Acausal
        }
    }

    fn name(self) -> &'static str {
        match self {
            Kind::SomRaychaudhuri => "Som–Raychaudhuri",
            Kind::Godel => "Gödel",
            Kind::Causal => "causal",
            Kind::Acausal => "closed timelike curves",
        }
    }
}

/// A tick step that puts at most four labels on each side of the origin.
fn tick_step(half: f64) -> f64 {
    let mut step = 0.25;
    while half / step > 4.0 {
        step *= 2.0;
    }
    step
}

/// A path covering the square [−big, big]² outside the circle of radius `r` about the
/// origin (even-odd rule), drawn with `style`.
fn outside(r: f64, big: f64, style: &str) -> String {
    format!(
        r#"<path fill-rule="evenodd" d="M{} {}H{}V{}H{}Z M{} 0A{} {} 0 1 0 {} 0A{} {} 0 1 0 {} 0Z" {style}/>"#,
        f(-big),
        f(-big),
        f(big),
        f(big),
        f(-big),
        f(r),
        f(r),
        f(r),
        f(-r),
        f(r),
        f(r),
        f(r)
    )
}

/// Whether a member's coordinates end (ρ = π/μ) within a frame of half-width `half`.
fn end_shown(g: GodelType, half: f64) -> bool {
    g.coordinate_radius()
        .is_some_and(|end| end * g.omega < std::f64::consts::SQRT_2 * half)
}

/// One member's frame: grid, ticks, the region of closed timelike curves (tinted), the
/// circle ρ_c, the coordinates' end, the rays with arrowheads and the origin. `ids` name the
/// frame's clip path and data layer.
fn draw_frame(s: &mut Svg, fr: &Frame, half: f64, rays: &MemberRays, ids: (&str, &str)) {
    let (left, top, side) = (fr.left, fr.top, fr.side);
    let step = tick_step(half);
    let count = (half / step).floor() as i64;
    for k in -count..=count {
        let v = k as f64 * step;
        let grid = r##"stroke="#ececec" stroke-width="1""##;
        s.line((fr.px(v), top), (fr.px(v), top + side), grid);
        s.line((left, fr.py(v)), (left + side, fr.py(v)), grid);
        let st = r##"stroke="#333" stroke-width="1""##;
        s.line((fr.px(v), top + side), (fr.px(v), top + side - 7.0), st);
        s.line((left, fr.py(v)), (left + 7.0, fr.py(v)), st);
        fr.tick_labels(s, v);
    }
    fr.open_data_layer_titled(s, ("Ω x", "Ω y"), ids);
    let g = rays.member;
    let w = g.omega;
    if let Some(rho_c) = g.critical_radius() {
        // The region of closed timelike curves, translucent over the grid.
        s.raw(&outside(
            rho_c * w,
            2.0 * half,
            &format!(r#"id="ctc-region" fill="{CTC_TINT}" fill-opacity="0.75""#),
        ));
    }
    if let Some(end) = g.coordinate_radius() {
        // Beyond ρ = π/μ there is no more of the chart: grey, with the circle where it ends.
        let r = end * w;
        s.raw(&outside(r, 2.0 * half, &format!(r#"fill="{BEYOND_TINT}""#)));
        s.circle(
            (0.0, 0.0),
            r,
            &format!(
                r##"id="coordinate-end" fill="none" stroke="#777" stroke-width="{}""##,
                f(fr.data(1.2))
            ),
        );
    }
    for (k, points) in rays.rays.iter().enumerate() {
        let colour = PALETTE[k % PALETTE.len()];
        s.polyline(
            points,
            &format!(
                r#"stroke="{colour}" stroke-width="{}" stroke-linejoin="round""#,
                f(fr.data(1.8))
            ),
        );
        // Arrowheads on the way out and back (escaping rays: within the frame).
        let fractions: &[f64] = if rays.return_time.is_some() {
            &[0.3, 0.7]
        } else {
            &[0.25, 0.5]
        };
        let n = points.len();
        for &frac in fractions {
            let i = ((n - 1) as f64 * frac).round() as usize;
            let (i0, i1) = (i.saturating_sub(1), (i + 1).min(n - 1));
            let d = (points[i1].0 - points[i0].0, points[i1].1 - points[i0].1);
            s.polygon(
                &arrowhead(points[i], d, fr.data(11.0)),
                &format!(r#"fill="{colour}""#),
            );
        }
    }
    if let Some(rho_c) = g.critical_radius() {
        s.circle(
            (0.0, 0.0),
            rho_c * w,
            &format!(
                r##"id="critical-radius" data-radius="{}" fill="none" stroke="#222" stroke-width="{}" stroke-dasharray="{} {}""##,
                f(rho_c * w),
                f(fr.data(1.6)),
                f(fr.data(7.0)),
                f(fr.data(5.0))
            ),
        );
    }
    s.circle((0.0, 0.0), fr.data(3.5), r##"fill="#222""##);
    fr.close_data_layer(s);
}

/// The legend's rows: rays, the circle ρ_c, the tinted region, the coordinates' end where a
/// member has one, the future direction.
fn legend(s: &mut Svg, legend: &mut Legend, n_rays: usize, members: &[GodelType], half: f64) {
    legend.swatches(
        s,
        n_rays,
        9.0,
        &format!("light rays in the plane z = 0 ({n_rays})"),
    );
    if members.iter().any(|g| g.critical_radius().is_some()) {
        let dashed = r##"stroke="#222" stroke-width="1.6" stroke-dasharray="7 5""##;
        legend.line(s, 72.0, dashed, "ρ = ρ_c, where the rays turn");
        let tint = format!(r##"stroke="{CTC_TINT}" stroke-width="12""##);
        legend.line(s, 72.0, &tint, "closed timelike curves (ρ > ρ_c)");
    }
    if members.iter().any(|&g| end_shown(g, half)) {
        let grey = r##"stroke="#777" stroke-width="1.2""##;
        legend.line(s, 72.0, grey, "ρ = π/μ: the coordinates end");
    }
    legend.arrow(s, 12.0, "#444", "future direction");
}

/// The caption's note where escaping rays stop before the frame's corner.
fn cut_note(all: &[MemberRays]) -> Vec<String> {
    match all.iter().find_map(|r| r.cut.map(|c| (r.member, c))) {
        Some((g, c)) => vec![format!(
            "(m² = {}: drawn to mρ = {}, Ωρ = {}.)",
            m2_text(g),
            f(ESCAPE_M_RHO),
            f(c)
        )],
        None => Vec::new(),
    }
}

/// One member's figure: the frame on the left, legend and caption on the right.
pub fn member_figure(rays: &MemberRays, n_rays: usize) -> String {
    let g = rays.member;
    let half = frame_half(&[g]);
    let fr = Frame::new(half);
    let mut s = fr.canvas("Light rays through the origin of a Gödel-type universe");
    draw_frame(&mut s, &fr, half, rays, ("frame", "data"));

    let x0 = fr.legend_left();
    let mut key = Legend::new(&mut s, x0, fr.top + 20.0, x0 + 80.0);
    legend(&mut s, &mut key, n_rays, &[g], half);
    let y = key.y;
    let mut lines = vec![format!(
        "Member m² = {} = {}, Ω = {}",
        tick_label(g.m2),
        m2_text(g),
        tick_label(g.omega)
    )];
    match Kind::of(g) {
        Kind::Godel => lines.push(format!(
            "(Gödel’s universe, a = 1/(√2 Ω) = {}).",
            f(g.godel_a())
        )),
        Kind::Acausal => {}
        kind => lines.push(format!("({}).", kind.name())),
    }
    match (g.critical_radius(), rays.return_time) {
        (Some(rho_c), Some(t)) => lines.extend([
            "Beyond ρ_c the circles about the axis".to_string(),
            "are closed timelike curves; each light ray".to_string(),
            "from the origin circles counter-clockwise,".to_string(),
            format!("turns at ρ_c = {}/Ω and returns to the", f(rho_c * g.omega)),
            format!("origin after Δt = {}/Ω (traced).", f(t)),
        ]),
        _ => lines.extend([
            "m² ≥ 4Ω²: no closed timelike curves; the".to_string(),
            "rays escape, drawn until they leave the".to_string(),
            "frame.".to_string(),
        ]),
    }
    lines.extend(cut_note(std::slice::from_ref(rays)));
    lines.extend([
        String::new(),
        "Axes: x = ρ cos φ, y = ρ sin φ, ρ the proper".to_string(),
        "radius, in units of 1/Ω.".to_string(),
        "Traced numerically (DOP853).".to_string(),
    ]);
    caption(&mut s, x0, y + 44.0, &lines);
    s.finish("Light rays through the origin of a Gödel-type universe")
}

/// Up to three members side by side at one Ω, in one frame size, with a label above each
/// and the legend and caption below.
pub fn members_figure(all: &[MemberRays], n_rays: usize) -> String {
    let members: Vec<GodelType> = all.iter().map(|r| r.member).collect();
    let half = frame_half(&members);
    let (side, gap, left0, top) = (340.0, 100.0, 90.0, 112.0);
    let width = left0 + all.len() as f64 * (side + gap) - gap + 40.0;
    let width = width.max(760.0);
    let below = top + side + 80.0;
    let omega = members[0].omega;
    let lines: Vec<String> = [
        format!("Ω = {} in every panel; axes x = ρ cos φ,", f(omega)),
        "y = ρ sin φ in units of 1/Ω, ρ the proper radius.".to_string(),
        "Where m² < 4Ω² the in-plane rays from the".to_string(),
        "origin turn at ρ_c, where closed timelike".to_string(),
        "curves begin, and come back; where m² ≥ 4Ω²".to_string(),
        "they escape (drawn until they leave the frame).".to_string(),
        "Traced numerically (DOP853).".to_string(),
    ]
    .into_iter()
    .chain(cut_note(all))
    .collect();
    // Room for the caption's lines (22 pixels apart) and the legend's six rows at most.
    let height = below + (22.0 * lines.len() as f64).max(160.0) + 12.0;
    let mut s = Svg::new(width, height);
    s.rect((0.0, 0.0), (width, height), r#"fill="white""#);
    let title = "Light rays through the origin of Gödel-type universes";
    s.text((left0, 38.0), 22.0, "start", r##"fill="#222""##, title);
    for (i, rays) in all.iter().enumerate() {
        let fr = Frame::at(left0 + i as f64 * (side + gap), top, side, half);
        let g = rays.member;
        let label = format!("m² = {} ({})", m2_text(g), Kind::of(g).name());
        let (cx, dark) = (fr.left + side / 2.0, r##"fill="#222""##);
        s.text_as(
            (cx, top - 36.0),
            17.0,
            Weight::Bold,
            0.0,
            "middle",
            dark,
            &label,
        );
        let sub = match g.critical_radius() {
            Some(rho_c) => format!("ρ_c = {}/Ω", f(rho_c * g.omega)),
            None => "no closed timelike curves".to_string(),
        };
        s.text((cx, top - 12.0), 15.0, "middle", r##"fill="#333""##, &sub);
        draw_frame(
            &mut s,
            &fr,
            half,
            rays,
            (&format!("frame-{i}"), &format!("data-{i}")),
        );
    }
    let mut key = Legend::new(&mut s, left0, below, left0 + 80.0);
    legend(&mut s, &mut key, n_rays, &members, half);
    let x = (left0 + 400.0).max(width - 420.0);
    caption(&mut s, x, below, &lines);
    s.finish(title)
}
