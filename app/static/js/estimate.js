// Before a run: how long will it take, will it hit the server's limits, and are there
// enough samples to see the motion? A pilot run of the same request over a short time
// (POST /api/simulate, t <= PILOT_T) measures the case's cost at these parameters and
// tolerances, and its state gives the time scale of the motion; both are extrapolated
// linearly in time (an adaptive integrator's step count grows about linearly with t).
"use strict";

import { api } from "./api.js";

const PILOT_T = 20;
const PILOT_SAMPLES = 401;
const PER_TURN = 8;        // samples per turn of the fastest component to draw it

/** The shortest period visible in the pilot: twice the mean spacing of the sign changes
 * of any state component about its mean. */
function shortestPeriod(t, state) {
  let best = Infinity;
  for (let j = 0; j < state[0].length; j++) {
    const xs = state.map((s) => s[j]);
    const mean = xs.reduce((a, b) => a + b, 0) / xs.length;
    const amp = Math.max(...xs.map((x) => Math.abs(x - mean)));
    if (!(amp > 1e-9)) continue;
    const cross = [];
    for (let i = 1; i < xs.length; i++) {
      if ((xs[i - 1] - mean) * (xs[i] - mean) < 0) cross.push(t[i]);
    }
    if (cross.length >= 2) best = Math.min(best, 2 * (cross[cross.length - 1] - cross[0]) / (cross.length - 1));
  }
  return best;
}

export async function estimate(req, limits) {
  const tp = Math.min(req.t_end, PILOT_T);
  const pilot = await api("/api/simulate", { method: "POST",
    body: { ...req, t_end: tp, samples: PILOT_SAMPLES } });
  const s = pilot.stats;
  const tReached = pilot.t[pilot.t.length - 1];
  if (!(tReached > 0) || !s.steps) return { level: "info", text: "" };
  const scale = req.t_end / tReached;
  const steps = Math.round(s.steps * scale);
  const secs = s.wall_s * scale;
  const lines = [`Estimate from a pilot run to t = ${+tReached.toPrecision(3)}: about ` +
    `${steps.toLocaleString("en")} steps, ${secs < 1 ? (secs * 1e3).toFixed(0) + " ms" : secs.toFixed(1) + " s"} of integration.`];
  let level = "info";
  if (steps > limits.max_steps) {
    level = "warn";
    lines.push(`It will stop at the server's step budget (${limits.max_steps.toLocaleString("en")} steps), near t ≈ ` +
      `${+(req.t_end * limits.max_steps / steps).toPrecision(3)}.`);
  }
  if (secs > limits.deadline_s) {
    level = "warn";
    lines.push(`It will exceed the server's deadline of ${limits.deadline_s} s per run: shorten t_end or loosen the tolerances.`);
  }
  const period = shortestPeriod(pilot.t, pilot.state);
  const dt = req.t_end / (req.samples - 1);
  if (Number.isFinite(period) && dt > period / PER_TURN) {
    level = "warn";
    const need = Math.ceil(req.t_end / (period / PER_TURN)) + 1;
    lines.push(`Too few samples to resolve the motion: it turns about every ${+period.toPrecision(2)} time units, ` +
      `the samples are ${+dt.toPrecision(2)} apart; ask for at least ${need.toLocaleString("en")} samples` +
      (need > limits.max_samples ? ` (more than the ${limits.max_samples} allowed: shorten t_end)` : "") + ".");
  }
  if (pilot.status !== "ok") { level = "warn"; lines.push(`The pilot stopped: ${pilot.message}`); }
  return { level, text: lines.join(" "), steps, secs, period };
}
