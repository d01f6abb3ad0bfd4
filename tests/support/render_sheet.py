"""Renders a drawing sheet's DXF (its paper-space layout, with the viewports
onto model space) or PDF (one page, the first unless given) to a PNG of a given width whose
pixels map onto the whole paper, for tests/drawing_render.rs to compare with
Chromium's rendering of the SVG.

    render_sheet.py dxf sheet.dxf out.png WIDTH_PX PAPER_W_MM PAPER_H_MM
    render_sheet.py pdf sheet.pdf out.png WIDTH_PX [PAGE]
"""

import sys


def render_dxf(path, out, width, paper_w, paper_h):
    import ezdxf
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from ezdxf.addons.drawing import Frontend, RenderContext
    from ezdxf.addons.drawing.matplotlib import MatplotlibBackend

    doc = ezdxf.readfile(path)
    names = [n for n in doc.layout_names_in_taborder() if n != "Model"]
    if not names:
        sys.exit("no paper-space layout")
    layout = doc.layouts.get(names[0])
    inches = (paper_w / 25.4, paper_h / 25.4)
    fig = plt.figure(figsize=inches)
    ax = fig.add_axes([0, 0, 1, 1])
    ctx = RenderContext(doc)
    ctx.set_current_layout(layout)
    Frontend(ctx, MatplotlibBackend(ax)).draw_layout(layout, finalize=True)
    ax.set_xlim(0, paper_w)
    ax.set_ylim(0, paper_h)
    ax.set_facecolor("white")
    fig.patch.set_facecolor("white")
    fig.set_size_inches(*inches)
    fig.savefig(out, dpi=width / inches[0], facecolor="white")


def render_pdf(path, out, width, page_index=0):
    import pymupdf

    page = pymupdf.open(path)[page_index]
    zoom = width / page.rect.width
    page.get_pixmap(matrix=pymupdf.Matrix(zoom, zoom), alpha=False).save(out)


if __name__ == "__main__":
    kind, path, out, width = sys.argv[1:5]
    if kind == "dxf":
        render_dxf(path, out, int(width), float(sys.argv[5]), float(sys.argv[6]))
    elif kind == "pdf":
        render_pdf(path, out, int(width), int(sys.argv[5]) if len(sys.argv) > 5 else 0)
    else:
        sys.exit(f"unknown kind {kind}")
