"""What the doc/scripts/render_*.py scripts share: drawing rbc-ifem's fields with VTK
and saving the view as a PNG, in one style. Reading the run's files is
rbc_ifem_run's (read_dataset, Run.series). Needs python3-paraview,
python3-matplotlib (for its colour maps) and the DejaVu fonts
(fonts-dejavu-core; `scripts/install-packages.sh --docs`).

Style: black DejaVu Sans text on white (VTK's own font has no µ, ⁻, ³ or →
and draws [ ] as ( )); smooth (Gouraud) shading on surfaces with normals;
perceptually uniform colour maps (viridis, cividis: colour_map), never a
rainbow, whose bright bands read as features that are not there; colour
bars with round ticks, the title above the bar and the ticks below;
parallel projection, so that a scale bar holds everywhere in a view.
"""
import math
import os

import vtk

FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
TEXT_SIZE = 20
BLACK = (0, 0, 0)
# VTK frees an algorithm whose Python object goes, even with a filter
# connected to its output: the filters made here are held until the end.
_HELD = []
# Flux of CO volume per membrane area and time: λ = αD ∂P/∂n (doc/diffusion.md).
FLUX_UNIT = "µm³ µm⁻² s⁻¹"


def use_font(*text_properties, size=None, colour=BLACK):
    """DejaVu Sans, black, SIZE points (if given) on every text property."""
    if not os.path.exists(FONT):
        raise SystemExit(f"{FONT} is missing: apt-get install fonts-dejavu-core")
    for text in text_properties:
        text.SetFontFamily(vtk.VTK_FONT_FILE)
        text.SetFontFile(FONT)
        text.SetColor(*colour)
        text.BoldOff()
        text.ItalicOff()
        text.ShadowOff()
        if size is not None:
            text.SetFontSize(size)


def label(renderer, text, x, y, size=TEXT_SIZE, justify="left", colour=BLACK):
    """TEXT at (X, Y) of the renderer's viewport, both from 0 to 1."""
    caption = vtk.vtkTextActor()
    caption.SetInput(text)
    properties = caption.GetTextProperty()
    use_font(properties, size=size, colour=colour)
    {"left": properties.SetJustificationToLeft, "centre": properties.SetJustificationToCentered,
     "right": properties.SetJustificationToRight}[justify]()
    caption.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    caption.SetPosition(x, y)
    renderer.AddActor2D(caption)
    return caption


def world_label(renderer, text, point, size=TEXT_SIZE, justify="centre", colour=BLACK):
    """TEXT at the world POINT (x, y, z), drawn over the scene, centred on
    it vertically."""
    caption = label(renderer, text, 0, 0, size, justify, colour)
    caption.GetTextProperty().SetVerticalJustificationToCentered()
    caption.GetPositionCoordinate().SetCoordinateSystemToWorld()
    caption.GetPositionCoordinate().SetValue(*point)
    return caption


def pointer(renderer, text, point, offset, size=TEXT_SIZE, colour=BLACK):
    """TEXT OFFSET (dx, dy) pixels from the world POINT, with a line from
    the text's near corner to the point."""
    caption = vtk.vtkCaptionActor2D()
    caption.SetCaption(text)
    caption.SetAttachmentPoint(*point)
    caption.BorderOff()
    caption.LeaderOn()
    caption.ThreeDimensionalLeaderOff()
    caption.GetProperty().SetColor(*colour)
    caption.GetProperty().SetLineWidth(1.5)
    caption.GetTextActor().SetTextScaleModeToNone()
    use_font(caption.GetCaptionTextProperty(), size=size, colour=colour)
    properties = caption.GetCaptionTextProperty()
    (properties.SetJustificationToLeft if offset[0] >= 0 else properties.SetJustificationToRight)()
    (properties.SetVerticalJustificationToBottom if offset[1] >= 0
     else properties.SetVerticalJustificationToTop)()
    caption.GetPositionCoordinate().SetCoordinateSystemToDisplay()
    caption.SetPosition(*offset)
    caption.SetWidth(0.01)
    caption.SetHeight(0.01)
    renderer.AddActor2D(caption)
    return caption


def outer_surface(algorithm_or_data):
    """The surface of a data set or of an algorithm's output, as polygons."""
    surface = vtk.vtkDataSetSurfaceFilter()
    _HELD.append(surface)
    if isinstance(algorithm_or_data, vtk.vtkAlgorithm):
        surface.SetInputConnection(algorithm_or_data.GetOutputPort())
    else:
        surface.SetInputData(algorithm_or_data)
    return surface


def smooth_surface(algorithm_or_data):
    """The surface as one mesh with smooth normals, for Gouraud shading
    (deal.II writes the vertices of every cell separately; merging them
    averages nothing, continuous fields agree there)."""
    merged = vtk.vtkCleanPolyData()
    _HELD.append(merged)
    merged.SetInputConnection(outer_surface(algorithm_or_data).GetOutputPort())
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputConnection(merged.GetOutputPort())
    normals.SplittingOff()
    normals.ConsistencyOn()
    return normals


def colour_map(low, high, vector=False, name="viridis"):
    """A lookup table from LOW to HIGH in matplotlib's perceptually uniform,
    sequential NAME (viridis or cividis: lightness grows with the value, so
    that the picture reads in grey and to colour-blind eyes; VTK has no
    such preset); values outside take the end colours. VECTOR: colour a
    vector array by its magnitude."""
    from matplotlib import colormaps  # here: the rest of this file needs only VTK
    colours = colormaps[name]
    table = vtk.vtkLookupTable()
    table.SetNumberOfTableValues(256)
    table.SetRange(low, high)
    for k in range(256):
        table.SetTableValue(k, *colours(k / 255))
    if vector:
        table.SetVectorModeToMagnitude()
    table.Build()  # keeps the values set (they are newer), adds the out-of-range colours
    return table


def colours_of(n, name="viridis"):
    """N colours (r, g, b) spread over matplotlib's NAME, dark to light: for
    things numbered in an order, such as the cells along the capillary."""
    from matplotlib import colormaps
    return [colormaps[name](k / max(n - 1, 1))[:3] for k in range(n)]


def non_negative_range(array, component=-1):
    """[0, largest] of a vtk ARRAY (its magnitude if COMPONENT is -1 and it
    has several): for quantities that are physically ≥ 0, whose small
    negative values are discretisation undershoot (doc/diffusion.md)."""
    return 0.0, array.GetRange(component)[1]


def actor(surface, array=None, value_range=None, lookup_table=None, component=None,
          flat=False):
    """An actor for a surface algorithm, coloured by a point array if one is
    named (by its magnitude if a vector, or by COMPONENT), Gouraud-shaded;
    FLAT: unlit, for a cut seen face-on, so that its colours are the scale's."""
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(surface.GetOutputPort())
    if array is None:
        mapper.ScalarVisibilityOff()
    else:
        mapper.SetScalarModeToUsePointFieldData()
        if component is None:
            mapper.SelectColorArray(array)
        else:
            mapper.ColorByArrayComponent(array, component)
        mapper.SetColorModeToMapScalars()
        mapper.SetScalarRange(*value_range)
        mapper.SetLookupTable(lookup_table)
        mapper.InterpolateScalarsBeforeMappingOn()
    result = vtk.vtkActor()
    result.SetMapper(mapper)
    result.GetProperty().SetInterpolationToGouraud()
    result.GetProperty().SetAmbient(0.15)
    result.GetProperty().SetDiffuse(0.85)
    result.GetProperty().SetSpecular(0.15)
    result.GetProperty().SetSpecularPower(20)
    if flat:
        result.GetProperty().LightingOff()
    return result


def solid_actor(algorithm, colour, line_width=None):
    """An actor that draws ALGORITHM's output in one COLOUR (arrows, outlines),
    with lines LINE_WIDTH pixels wide if given."""
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(algorithm.GetOutputPort())
    mapper.ScalarVisibilityOff()
    result = vtk.vtkActor()
    result.SetMapper(mapper)
    result.GetProperty().SetColor(*colour)
    if line_width is not None:
        result.GetProperty().SetLineWidth(line_width)
    return result


def nice_ticks(low, high, most=6):
    """Round numbers from LOW to HIGH, at most MOST of them, 1-2-2.5-5 apart."""
    if high <= low:
        return [low]
    rough = (high - low) / (most - 1)
    power = 10 ** math.floor(math.log10(rough))
    step = next(s * power for s in (1, 2, 2.5, 5, 10) if s * power >= rough * (1 - 1e-9))
    first = math.ceil(low / step - 1e-9)
    last = math.floor(high / step + 1e-9)
    return [k * step for k in range(first, last + 1)]


def legend(lookup, title, viewport, width=0.6, label_format="%.4g", ticks=None):
    """A renderer over VIEWPORT (x0, y0, x1, y1 of the window) holding a
    horizontal colour bar WIDTH of it wide: TITLE above, round ticks below."""
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    renderer.SetViewport(*viewport)
    low, high = lookup.GetRange()
    values = vtk.vtkDoubleArray()
    for value in ticks or nice_ticks(low, high):
        values.InsertNextValue(0.0 if abs(value) < 1e-12 * (high - low) else value)
    bar = vtk.vtkScalarBarActor()
    bar.SetLookupTable(lookup)
    bar.SetOrientationToHorizontal()
    bar.SetTitle("")
    bar.UseCustomLabelsOn()
    bar.SetCustomLabels(values)
    bar.SetLabelFormat(label_format)
    bar.SetTextPositionToPrecedeScalarBar()  # ticks below the bar
    bar.UnconstrainedFontSizeOn()
    bar.DrawTickLabelsOn()
    bar.SetBarRatio(0.45)
    bar.SetTextPad(4)
    bar.SetMaximumNumberOfColors(256)
    use_font(bar.GetLabelTextProperty(), size=TEXT_SIZE - 2)
    use_font(bar.GetTitleTextProperty(), size=TEXT_SIZE)
    bar.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    bar.SetPosition((1 - width) / 2, 0.02)
    bar.SetWidth(width)
    bar.SetHeight(0.62)
    renderer.AddActor2D(bar)
    label(renderer, title, 0.5, 0.7, justify="centre")
    return renderer


def parallel_camera(renderer, focal_point, direction, view_up, height):
    """Look along DIRECTION at FOCAL_POINT, parallel projection, HEIGHT [µm]
    of the scene filling the view's height."""
    camera = renderer.GetActiveCamera()
    camera.ParallelProjectionOn()
    camera.SetFocalPoint(*focal_point)
    norm = math.sqrt(sum(d * d for d in direction))
    camera.SetPosition(*(f - 100 * d / norm for f, d in zip(focal_point, direction)))
    camera.SetViewUp(*view_up)
    camera.SetParallelScale(height / 2)
    renderer.ResetCameraClippingRange()


def scale_bar(renderer, length, window_size, x=0.05, y=0.06, text=None, colour=BLACK):
    """A bar LENGTH µm long from (X, Y) of the renderer's viewport to the
    right, with its length written above it. The renderer's camera must
    have its parallel projection set (parallel_camera); WINDOW_SIZE is the
    picture's (width, height) in pixels."""
    x0, y0, x1, y1 = renderer.GetViewport()
    width, height = (x1 - x0) * window_size[0], (y1 - y0) * window_size[1]
    scale = renderer.GetActiveCamera().GetParallelScale()
    across = length / (2 * scale) * height / width  # of the viewport's width
    points = vtk.vtkPoints()
    for px in (x, x + across):
        points.InsertNextPoint(px, y, 0)
    ends = 0.012 * width / height  # little upright ticks at the ends
    for px in (x, x + across):
        points.InsertNextPoint(px, y - ends * height / width, 0)
        points.InsertNextPoint(px, y + ends * height / width, 0)
    lines = vtk.vtkCellArray()
    for a, b in ((0, 1), (2, 3), (4, 5)):
        lines.InsertNextCell(2)
        lines.InsertCellPoint(a)
        lines.InsertCellPoint(b)
    bar = vtk.vtkPolyData()
    bar.SetPoints(points)
    bar.SetLines(lines)
    coordinate = vtk.vtkCoordinate()
    coordinate.SetCoordinateSystemToNormalizedViewport()
    mapper = vtk.vtkPolyDataMapper2D()
    mapper.SetInputData(bar)
    mapper.SetTransformCoordinate(coordinate)
    drawn = vtk.vtkActor2D()
    drawn.SetMapper(mapper)
    drawn.GetProperty().SetColor(*colour)
    drawn.GetProperty().SetLineWidth(3)
    renderer.AddActor2D(drawn)
    label(renderer, text or f"{length:g} µm", x + across / 2, y + 0.025, size=TEXT_SIZE - 2,
          justify="centre", colour=colour)


def save_png(renderers, picture, size):
    """Render RENDERERS (one window, each in its viewport) off a virtual
    display and write PICTURE."""
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    for renderer in renderers:
        renderer.UseFXAAOn()
        window.AddRenderer(renderer)
    window.SetSize(*size)
    window.Render()
    image = vtk.vtkWindowToImageFilter()
    image.SetInput(window)
    image.ReadFrontBufferOff()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(picture)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()
    print("wrote", picture)
