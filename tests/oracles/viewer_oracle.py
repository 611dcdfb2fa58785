"""plan.html drawn by a real browser: headless Chromium loads the demo's viewer from disk
(offline: no server, no network) and the DOM after its scripts ran must hold one drawn
Leaflet shape per feature of plan.geojson and a layer per sortie. A screenshot is left in
the scratch folder named on stdout for a person to look at.

Run: python tests/oracles/viewer_oracle.py target/debug/agripath [CHROMIUM]
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

AGRIPATH = sys.argv[1]
CHROMIUM = sys.argv[2] if len(sys.argv) > 2 else (shutil.which("chromium") or shutil.which("chromium-browser"))
if not CHROMIUM:
    print("viewer: FAILED: no chromium on PATH (.ci/run installs Debian's chromium)")
    sys.exit(1)

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--virtual-time-budget=5000", "--window-size=1400,900"]

scratch = tempfile.mkdtemp(prefix="agripath-viewer-")
demo = os.path.join(scratch, "demo")
subprocess.run([AGRIPATH, "demo", "--out", demo], check=True, stdout=subprocess.DEVNULL)
page = "file://" + os.path.join(demo, "plan.html")
profile = os.path.join(scratch, "profile")
dom = subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", "--dump-dom", page],
                     check=True, capture_output=True, text=True, timeout=120).stdout
subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", "--screenshot=" + os.path.join(scratch, "plan.png"), page],
               check=True, capture_output=True, timeout=120)

with open(os.path.join(demo, "plan.geojson")) as handle:
    features = json.load(handle)["features"]
with open(os.path.join(demo, "report.json")) as handle:
    sorties = json.load(handle)["sorties"]

failures = []
drawn = len(re.findall(r'<path[^>]*class="[^"]*leaflet-interactive', dom))
if f'data-features="{len(features)}"' not in dom:
    failures.append("the page script did not finish (data-features missing)")
if drawn != len(features):
    failures.append(f"{drawn} shapes drawn for {len(features)} features")
layers = re.findall(r"<span> sortie (\d+)</span>", dom)
if sorted(map(int, layers)) != list(range(1, sorties + 1)):
    failures.append(f"sortie layers {layers}, report has {sorties} sorties")
if "leaflet-image-layer" not in dom:
    failures.append("no hillshade overlay")
if 'href="sheet.html"' not in dom:
    failures.append("the viewer does not link to the mission sheet")

# A field named with markup (trial 7): the viewer shows the name as text when its popup
# opens, and runs nothing from it.
hostile = os.path.join(scratch, "hostile.geojson")
payload = 'North<img src=x onerror="document.body.dataset.pwned=1">'
with open(hostile, "w") as handle:
    json.dump({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": payload},
               "geometry": {"type": "Polygon", "coordinates": [[[9.95, 49.8], [9.9528, 49.8], [9.9528, 49.8011],
                                                                [9.95, 49.8011], [9.95, 49.8]]]}}]}, handle)
named = os.path.join(scratch, "named")
subprocess.run([AGRIPATH, "plan", "--fields", hostile, "--out", named], check=True, stdout=subprocess.DEVNULL)
with open(os.path.join(named, "plan.html")) as handle:
    viewer = handle.read()
opener = ("<script>setTimeout(() => { for (const g of groups.values()) g.eachLayer(l => l.eachLayer && "
          "l.eachLayer(x => { if (x.feature && x.feature.properties.kind === 'field') x.openPopup(); })); }, 300);"
          "</script>")
with open(os.path.join(named, "probe.html"), "w") as handle:
    handle.write(viewer.replace("</body>", opener + "</body>"))
probed = subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", "--dump-dom",
                         "file://" + os.path.join(named, "probe.html")],
                        check=True, capture_output=True, text=True, timeout=120).stdout
if "data-pwned" in probed:
    failures.append("a field's name ran as markup in the viewer's popup")
if "North&lt;img" not in probed:
    failures.append("the field's popup did not open with its name as text")

# The mission sheet printed by the same browser: agripath's --pdf finds it through
# AGRIPATH_BROWSER; the PDF must be a PDF of two pages or more (the table, then the map).
printed = os.path.join(scratch, "printed")
run = subprocess.run([AGRIPATH, "demo", "--pdf", "--out", printed], capture_output=True, text=True,
                     env={**os.environ, "AGRIPATH_BROWSER": CHROMIUM}, timeout=300)
pdf_path = os.path.join(printed, "sheet.pdf")
if run.returncode != 0 or not os.path.isfile(pdf_path):
    failures.append(f"demo --pdf wrote no sheet.pdf: {run.stdout[-300:]} {run.stderr[-300:]}")
    pages = 0
else:
    with open(pdf_path, "rb") as handle:
        pdf = handle.read()
    pages = len(re.findall(rb"/Type\s*/Page[^s]", pdf))
    if not pdf.startswith(b"%PDF") or pages < 2:
        failures.append(f"sheet.pdf: {pages} page(s), header {pdf[:8]!r}")
    subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", "--screenshot=" + os.path.join(scratch, "sheet.png"),
                    "file://" + os.path.join(printed, "sheet.html")], check=True, capture_output=True, timeout=120)
for failure in failures:
    print("FAILED:", failure)
print(f"viewer: {drawn} shapes for {len(features)} features, {len(layers)} sortie layers; screenshot {scratch}/plan.png; sheet.pdf {pages} page(s), screenshot {scratch}/sheet.png")
sys.exit(1 if failures else 0)
