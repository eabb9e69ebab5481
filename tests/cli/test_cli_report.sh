# `blocklab report` on two small runs of the bundled samples (Banterle 2008 Table 1's config, which has a published
# table, and a munkberg run with mode maps): index.html and report.md are written, the paper table holds the
# published values beside ours, every <img> of the page is a readable PNG beside it, the page loads nothing from the
# network, and in headless Chromium (Debian package chromium) the page renders: the DOM has the tables and the SVG
# plots, the console logs no message, and the screenshot is not blank. Without chromium the browser part is skipped
# (exit 77) after the other checks.
source "$(dirname "$0")/common.sh"
cd "$SOURCE_DIR"
"$BLOCKLAB" run configs/papers/banterle2008/table1.yaml --data-root samples --out "$WORK/banterle" -q >/dev/null
cat >"$WORK/modes.yaml" <<'YAML'
schema: 1
name: report_mode_maps
description: "munkberg with every mode and its mode maps, for the report test"
images: [hdr/Desk.exr]
mode_maps: true
metrics: [log2rgb, mpsnr]
formats:
  - format: munkberg
    options: {preset: fast, modes: [both, all]}
YAML
"$BLOCKLAB" run "$WORK/modes.yaml" --data-root samples --out "$WORK/modes" -q >/dev/null
"$BLOCKLAB" report "$WORK/banterle" "$WORK/modes" --out "$WORK/report" --thumbnail-size 64 2>"$WORK/progress.txt" \
  >/dev/null || die "report failed: $(cat "$WORK/progress.txt")"
grep -q "ETA" "$WORK/progress.txt" || die "no progress with an ETA: $(cat "$WORK/progress.txt")"
[ -s "$WORK/report/index.html" ] && [ -s "$WORK/report/report.md" ] || die "index.html or report.md missing"
/usr/bin/python3 - "$WORK/report" <<'PY'
import pathlib, re, sys
from PIL import Image
out = pathlib.Path(sys.argv[1])
html = (out / "index.html").read_text()
md = (out / "report.md").read_text()
bare = html.replace('xmlns="http://www.w3.org/2000/svg"', "")
assert "<script" not in bare and "http://" not in bare and "https://" not in bare, "page loads something or runs code"
for text in (html, md):
    assert "Table 1: averages" in text and "0.581" in text, "banterle published table missing"
    assert "Run 2: report_mode_maps" in text, "second run missing"
assert html.count("<svg") >= 3, html.count("<svg")
images = re.findall(r'<img src="([^"]+)"', html)
assert len(images) >= 2 * 4 * 3, len(images)
assert any(src.endswith("_modes.png") for src in images), "no mode map on the page"
for src in images + re.findall(r"\]\((img/[^)]+)\)", md):
    path = out / src
    assert path.is_file(), f"broken image {src}"
    if src.endswith(".png"):
        Image.open(path).verify()
# The published values in the table: banterle 4 bpp skip-rule log2[RGB] beside ours with a delta.
row = [l for l in md.splitlines() if "4 bpp (w/o residuals) log2[RGB]" in l][0].split("|")
assert row[3].strip() == "0.581" and float(row[4]) > 0 and row[5].strip().startswith(("+", "-")), row
print(f"ok: {len(images)} images on the page")
PY
expect_error "no-such-run: not a run folder" "$BLOCKLAB" report "$WORK/banterle" "$WORK/no-such-run" --out "$WORK/r2"
expect_error "report: --out is required" "$BLOCKLAB" report "$WORK/banterle"
if ! command -v chromium >/dev/null 2>&1; then
  echo "SKIPPED: chromium is not installed (scripts/install-deps.sh installs it): the page was not rendered"
  exit 77
fi
browser() { timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --enable-logging=stderr --v=0 \
  --user-data-dir="$WORK/chromium" "$@" "file://$WORK/report/index.html"; }
browser --dump-dom >"$WORK/dom.html" 2>"$WORK/dom.log" || die "chromium --dump-dom failed: $(tail -5 "$WORK/dom.log")"
browser --window-size=1280,1600 --screenshot="$WORK/shot.png" >/dev/null 2>"$WORK/shot.log" \
  || die "chromium --screenshot failed: $(tail -5 "$WORK/shot.log")"
if grep -h "CONSOLE" "$WORK/dom.log" "$WORK/shot.log"; then die "the page logged to the console"; fi
/usr/bin/python3 - "$WORK/dom.html" "$WORK/shot.png" <<'PY'
import sys
from PIL import Image
dom = open(sys.argv[1]).read()
assert dom.count("<table") >= 4 and dom.count("<svg") >= 3 and "Paper tables" in dom, "DOM lacks tables or plots"
shot = Image.open(sys.argv[2]).convert("RGB")
assert shot.size == (1280, 1600), shot.size
colours = shot.getcolors(1 << 20)
assert colours is not None and len(colours) > 50, f"screenshot looks blank: {len(colours or [])} colours"
white = max(count for count, colour in colours if colour == (255, 255, 255)) if any(c == (255, 255, 255) for _, c in colours) else 0
assert white < 0.97 * shot.size[0] * shot.size[1], "screenshot almost all white"
print(f"ok: rendered, {len(colours)} colours in the screenshot")
PY
