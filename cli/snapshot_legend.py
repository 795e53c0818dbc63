#!/usr/bin/python3
"""Adds a legend strip to a sumo-gui screenshot (`taebp snapshot` calls this):
the picture on top, below it a title line with the simulated time and one
swatch per vehicle colour with its meaning. sumo-gui cannot draw a legend, so
it is composed afterwards, headless, with Debian's python3-pil.

  snapshot_legend.py IN.png OUT.png --title TEXT --time SECONDS
                     --entry R,G,B=LABEL [--entry ...]
"""
import argparse
import sys


def font(size):
    from PIL import ImageFont
    try:  # DejaVu Sans: matplotlib's default font, found through its font manager
        from matplotlib import font_manager
        return ImageFont.truetype(font_manager.findfont("DejaVu Sans"), size)
    except Exception:  # noqa: BLE001 - any failure: PIL's own font
        for path in ("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",):
            try:
                return ImageFont.truetype(path, size)
            except OSError:
                pass
        return ImageFont.load_default()


def entry(text):
    rgb, _, label = text.partition("=")
    parts = rgb.split(",")
    if len(parts) != 3 or not label:
        raise argparse.ArgumentTypeError("expected R,G,B=LABEL, got %r" % text)
    return tuple(int(p) for p in parts), label


def main(argv=None):
    ap = argparse.ArgumentParser(prog="snapshot_legend.py")
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("--title", default="")
    ap.add_argument("--time", type=float, required=True, help="simulated time (s)")
    ap.add_argument("--entry", type=entry, action="append", default=[])
    args = ap.parse_args(argv)
    try:
        from PIL import Image, ImageDraw
    except ImportError:
        print("snapshot_legend.py: PIL is missing for %s: install the Debian package python3-pil "
              "(tools/setup.sh does)" % sys.executable, file=sys.stderr)
        return 1
    shot = Image.open(args.input).convert("RGB")
    w, h = shot.size
    text_font, small = font(17), font(15)
    pad, swatch, row = 12, 16, 26
    # Lay the entries out in rows that fit the picture's width.
    probe = ImageDraw.Draw(Image.new("RGB", (1, 1)))
    layout, x, y = [], pad, 0
    for rgb, label in args.entry:
        width = swatch + 6 + int(probe.textlength(label, font=small)) + 22
        if x + width > w - pad and x > pad:
            x, y = pad, y + row
        layout.append((x, y, rgb, label))
        x += width
    strip = pad + row + (y + row) + pad // 2
    out = Image.new("RGB", (w, h + strip), "white")
    out.paste(shot, (0, 0))
    d = ImageDraw.Draw(out)
    d.line([(0, h), (w, h)], fill=(160, 160, 160), width=1)
    time_text = "t = %g s (simulated)" % args.time
    d.text((pad, h + pad // 2 + 2), args.title, fill="black", font=text_font)
    d.text((w - pad - d.textlength(time_text, font=text_font), h + pad // 2 + 2), time_text,
           fill="black", font=text_font)
    top = h + pad // 2 + row + 4
    for x, y, rgb, label in layout:
        d.rectangle([x, top + y + 2, x + swatch, top + y + 2 + swatch], fill=rgb, outline=(60, 60, 60))
        d.text((x + swatch + 6, top + y), label, fill="black", font=small)
    out.save(args.output, "PNG")
    return 0


if __name__ == "__main__":
    sys.exit(main())
