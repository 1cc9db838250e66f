"""Browser: the 3D view of every teaching scene frames its body (app/static/js/scene.js,
issue 20: a small ball under 200-300 px of empty space). The body alone is drawn again
with the view's own camera (the other traces, the legend and the axes hidden; Plotly's
toImage), and the box of its pixels is measured against the plot's."""

import pytest

from catalogue.scenes import load_scenes

# Pause, keep only the body, draw the view as a PNG and find the box of the pixels that
# are not the white background. Returns that box and the plot's size, in px.
BODY_BOX = """async (sel) => {
  const el = document.querySelector(sel);
  document.getElementById('play').click();            // pause: no frame drawn meanwhile
  const body = el.data.findIndex((t) => t.type === 'mesh3d' && t.name === 'body');
  await Plotly.restyle(el, { visible: el.data.map((_, i) => i === body) });
  await Plotly.relayout(el, { showlegend: false, 'scene.xaxis.visible': false,
    'scene.yaxis.visible': false, 'scene.zaxis.visible': false });
  const W = el.clientWidth, H = el.clientHeight;
  const img = new Image();
  img.src = await Plotly.toImage(el, { format: 'png', width: W, height: H });
  await img.decode();
  const c = document.createElement('canvas');
  c.width = W; c.height = H;
  const g = c.getContext('2d');
  g.drawImage(img, 0, 0);
  const px = g.getImageData(0, 0, W, H).data;
  let x0 = W, y0 = H, x1 = -1, y1 = -1;
  for (let y = 0; y < H; y++) for (let x = 0; x < W; x++) {
    const o = 4 * (y * W + x);
    if (px[o + 3] > 0 && Math.min(px[o], px[o + 1], px[o + 2]) < 235) {
      x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
    }
  }
  return { W, H, x0, y0, x1, y1, body };
}"""


@pytest.mark.parametrize("scene_id", list(load_scenes()))
def test_the_3d_view_frames_the_body(page, server, scene_id):
    page.set_viewport_size({"width": 1280, "height": 720})
    page.goto(f"{server}/scenes#{scene_id}")
    page.locator(f"body[data-playing='{scene_id}']").wait_for(state="attached",
                                                               timeout=120_000)
    b = page.evaluate(BODY_BOX, "#scene-plot")
    assert b["body"] >= 0 and b["x1"] > b["x0"] and b["y1"] > b["y0"], b
    w, h = (b["x1"] - b["x0"]) / b["W"], (b["y1"] - b["y0"]) / b["H"]
    # the body spans a good part of the view one way or the other (a long stone lies
    # flat: its width counts), and no band above it is emptier than the body is tall
    assert max(w, h) >= 0.35, (scene_id, round(w, 2), round(h, 2), b)
    # within the view: not cut off at an edge
    assert b["x0"] > 0 and b["y0"] > 0 and b["x1"] < b["W"] - 1, b
