// Thumbnails of the teaching scenes on /scenes: a small SVG of each scene's body drawn from
// its own parameters and initial state (catalogue/scenes.yaml), no image files: a ball with
// its centre of mass where the parameters put it, a coin at its starting tilt, the
// rattleback's half-ellipsoid with its semi-axes, the ball over its fixed ball, a marble
// ball beside a rubber one.
"use strict";

const W = 120, H = 84, FLOOR = 72;
const INK = "#1b1f24", BODY = "#2b5d8a", CM = "#c21c2c", PATH = "#d97706";

const f = (x) => x.toFixed(1);

function svg(inner, label) {
  return `<svg class="scene-thumb" data-testid="scene-thumb" viewBox="0 0 ${W} ${H}" width="${W}" height="${H}"
    role="img" aria-label="${label}" xmlns="http://www.w3.org/2000/svg">${inner}</svg>`;
}

const floor = `<line x1="4" y1="${FLOOR}" x2="${W - 4}" y2="${FLOOR}" stroke="${INK}" stroke-width="2"/>`;

// a ball of radius r (px) on the floor, its centre of mass at offset (ax, az) in units of R
function ball(p, r = 30) {
  const cx = W / 2, cy = FLOOR - r;
  const ax = (p.a1 || 0), az = -(p.a3 !== undefined ? p.a3 : (p.a || 0));
  // an ellipse inside the ball: the inertia's shape (semi-axes as 1/sqrt of the moments)
  const k = 1 / Math.sqrt(p.I1 || 1), l = 1 / Math.sqrt(p.I3 || p.I2 || 1);
  const s = 0.75 * r / Math.max(k, l);
  return `${floor}<circle cx="${cx}" cy="${f(cy)}" r="${r}" fill="#dbe7f3" stroke="${BODY}" stroke-width="2.5"/>
    <ellipse cx="${cx}" cy="${f(cy)}" rx="${f(s * k)}" ry="${f(s * l)}" fill="none" stroke="#f0c419" stroke-width="2"/>
    <circle cx="${f(cx + ax * r)}" cy="${f(cy - az * r)}" r="4.5" fill="${CM}"/>
    <path d="M${cx - 42} ${FLOOR + 6} q 42 -4 84 0" fill="none" stroke="${PATH}" stroke-width="2.5"/>`;
}

function disk(p, state) {
  // the tilt of the coin from the vertical at the start: its axis makes acos(g3) with it
  const tilt = Math.asin(Math.min(1, Math.abs(state[5]))) || 0;
  const r = 30, cx = W / 2 + r * Math.sin(tilt), cy = FLOOR - r * Math.cos(tilt);
  const deg = (tilt * 180) / Math.PI;
  return `${floor}<ellipse cx="${f(cx)}" cy="${f(cy)}" rx="6" ry="${r}" transform="rotate(${f(deg)} ${f(cx)} ${f(cy)})"
    fill="#dbe7f3" stroke="${BODY}" stroke-width="2.5"/>
    <line x1="${W / 2}" y1="${FLOOR}" x2="${W / 2}" y2="${FLOOR - 2 * r - 6}" stroke="#8c959f" stroke-dasharray="3 3"/>
    <path d="M${W / 2 - 40} ${FLOOR + 6} q 40 8 80 0" fill="none" stroke="${PATH}" stroke-width="2.5"/>`;
}

function rattleback(p) {
  // semi-axes sqrt(b1) (long) and sqrt(b3) (height) of the ellipsoid, scaled to the box
  const a = Math.sqrt(p.b1), c = Math.sqrt(p.b3), s = 48 / a;
  const rx = a * s, ry = Math.max(8, c * s * 4);
  const cx = W / 2;
  const turn = (p.delta * 180) / Math.PI;
  // the lower half of the ellipse, resting on the floor; the yellow line is the long axis
  // of inertia, turned (exaggerated eightfold) against the shape's long axis
  const top = FLOOR - ry;
  return `${floor}<path d="M${f(cx - rx)} ${f(top)} A ${f(rx)} ${f(ry)} 0 0 0 ${f(cx + rx)} ${f(top)} Z"
    fill="#dbe7f3" stroke="${BODY}" stroke-width="2.5"/>
    <line x1="${f(cx - 0.8 * rx)}" y1="${f(top + 3)}" x2="${f(cx + 0.8 * rx)}" y2="${f(top + 3)}"
      transform="rotate(${f(-8 * Math.max(turn, 0.2))} ${cx} ${f(top + 3)})" stroke="#f0c419" stroke-width="2"/>
    <path d="M${cx - 18} 22 a 18 7 0 1 1 10 6" fill="none" stroke="${PATH}" stroke-width="2.5"/>
    <path d="M${cx - 8} 28 l -6 1 l 3 -6" fill="none" stroke="${PATH}" stroke-width="2.5"/>`;
}

function overSphere(p) {
  // the rolling shell (radius R) over the fixed ball of half its radius, touching it
  const R = 34, cx = W / 2, cy = H / 2 + 2;
  return `<circle cx="${cx}" cy="${cy}" r="${R}" fill="#dbe7f3" fill-opacity=".5" stroke="${BODY}" stroke-width="2.5"/>
    <circle cx="${cx}" cy="${cy + R / 2}" r="${R / 2}" fill="#b3bcc6" stroke="${INK}" stroke-width="1.5"/>
    <circle cx="${cx}" cy="${cy}" r="4" fill="${CM}"/>`;
}

// a marble ball (left, twisting about the vertical: a curled arrow) beside a rubber ball
// (right, darker, that does not twist: a crossed-out curl), each with its inertia ellipse
function pair(p) {
  const r = 22, cy = FLOOR - r;
  const one = (cx, fill, stroke) => {
    const k = 1 / Math.sqrt(p.I1 || 1), l = 1 / Math.sqrt(p.I3 || p.I2 || 1);
    const s = 0.75 * r / Math.max(k, l);
    return `<circle cx="${cx}" cy="${cy}" r="${r}" fill="${fill}" stroke="${stroke}" stroke-width="2.5"/>
      <ellipse cx="${cx}" cy="${cy}" rx="${f(s * k)}" ry="${f(s * l)}" fill="none" stroke="#f0c419" stroke-width="2"/>
      <path d="M${cx - 12} ${cy - r - 7} a 12 4 0 1 1 7 3" fill="none" stroke="${PATH}" stroke-width="2.2"/>`;
  };
  const L = 32, R = W - 32;
  return `${floor}${one(L, "#dbe7f3", BODY)}${one(R, "#3a3f44", INK)}
    <line x1="${R - 14}" y1="${cy - r - 2}" x2="${R + 14}" y2="${cy - r - 14}" stroke="${CM}" stroke-width="2.5"/>`;
}

/** The thumbnail of scene `s` (a preset of GET /api/scenes) as SVG markup. */
export function thumbnail(s) {
  const sc = s.scene, p = sc.params, kind = sc.case.split("/")[1];
  let inner;
  if (s.beside) inner = pair(p);
  else if (sc.case.startsWith("sphere/")) inner = overSphere(p);
  else if (kind === "round-disk") inner = disk(p, sc.state);
  else if (kind === "rattleback") inner = rattleback(p);
  else inner = ball(p);
  return svg(inner, s.beside ? `sketch of the bodies: ${sc.case} beside ${s.beside.case}`
    : `sketch of the body: ${sc.case}`);
}
