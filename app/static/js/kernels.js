// The kernels' compile in the background (GET /api/health's "kernels": app/services/
// kernel_warmup.py), in plain words for the home page and the case pages, and the label of a
// run that compiles its kernels first (POST /api/simulate/compiles, /api/scene/compiles).
import { api } from "./api.js";

// caseId: the case page's case (null on the home page)
export function kernelSentence(k, caseId = null) {
  if (!k || !["starting", "running"].includes(k.state)) {
    return k && k.state === "failed" ? `Kernels: ${k.message}` : "";
  }
  const about = `about ${Math.round(k.estimate_s)} s`;
  const parts = k.state === "starting" ? "listing what this machine has not compiled yet"
    : `${k.parts_done} of ${k.parts_total} parts compiled`;
  if (caseId === null) {
    return `Kernels: ${parts}, in the background. A run of a case still warming compiles its ` +
      `kernel before it starts (${about}, first use on this machine); the rest run at once.`;
  }
  const warming = k.state === "starting" || k.warming_cases.includes(caseId) ||
    k.warming_parts.includes("general kernels");
  return warming
    ? `Kernels: ${parts}; a run of this case compiles its kernel before it starts (${about}, ` +
      "first use on this machine)."
    : `Kernels: ${parts}; this case's are ready.`;
}

// the progress label of a run: "compiling … (first use on this machine), then <label>" when
// the server will compile the run's kernels first (outside the run's time limit)
export async function runLabel(path, body, label) {
  try {
    const c = await api(`${path}/compiles`, { method: "POST", body });
    if (c.compiles) {
      return `compiling the kernels of this run (first use on this machine, about ` +
        `${Math.round(c.estimate_s)} s; not counted in the time limit), then ${label}`;
    }
  } catch {
    // the run itself reports a bad request
  }
  return label;
}
