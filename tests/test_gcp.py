"""rsgeo.gcp against GDAL's GCP transformer, plus .points files and errors."""

import os

import numpy as np
import pytest

from rsgeo import data, gcp


def test_points_file_round_trip(tmp_path):
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    gcps.enabled[3] = False
    model = gcps.fit(1)
    path = tmp_path / "ccd.points"
    gcp.write_points(path, gcps, model)
    again = gcp.read_points(path)
    np.testing.assert_array_equal(again.map_xy, gcps.map_xy)
    np.testing.assert_array_equal(again.image_xy, gcps.image_xy)
    np.testing.assert_array_equal(again.enabled, gcps.enabled)
    assert again.crs == gcps.crs
    header = path.read_text().splitlines()[1]
    # QGIS's columns first (QgsGCPList::loadGcps reads only the first five), then ids and notes
    assert header == "mapX,mapY,sourceX,sourceY,enable,dX,dY,residual,id,note"


def test_reads_qgis_files_new_and_old(tmp_path):
    # Written by hand after QGIS Georeferencer's format: sourceY is minus the line number.
    new = tmp_path / "new.points"
    new.write_text("#CRS: EPSG:31983\n"
                   "mapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n"
                   "330000.5,7390000.25,10.5,-20.25,1,0.1,-0.2,0.22\n"
                   "331000,7389000,110,-120,0,0,0,0\n"
                   "332000,7391000,210,-20,1,0,0,0\n")
    gcps = gcp.read_points(new)
    assert gcps.crs == "EPSG:31983"
    np.testing.assert_array_equal(gcps.image_xy[0], [10.5, 20.25])
    np.testing.assert_array_equal(gcps.map_xy[0], [330000.5, 7390000.25])
    assert gcps.enabled.tolist() == [True, False, True]
    old = tmp_path / "old.points"
    old.write_text("mapX\tmapY\tpixelX\tpixelY\tenable\n330000\t7390000\t10\t-20\t1\n"
                   "331000\t7389000\t110\t-120\t1\n332000\t7391000\t210\t-20\t1\n")
    assert gcp.read_points(old).image_xy[1].tolist() == [110.0, 120.0]


# -- Coefficient standard errors, checks against a geotransform, silent failures ----------


def test_residual_arrows_point_down_the_image_for_positive_dy():
    # rows grow downwards: a GCP whose model position is 5 rows lower must draw downwards on screen
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rsgeo.plot import draw_residual_arrows, label_points, show_image

    from figure_audit import figure_problems

    figure, ax = plt.subplots()
    show_image(ax, np.zeros((100, 100)), title="arrows")
    arrows = draw_residual_arrows(ax, [[50.0, 50.0]], [0.0], [5.0], exaggeration=4)
    figure.canvas.draw()
    outline = arrows.get_transform().transform(arrows.get_paths()[0].vertices)  # display units
    tail, tip = ax.transData.transform([[50.0, 50.0], [50.0, 50.0 + 5.0 * 4]])
    assert tip[1] < tail[1]                       # display y grows upwards: down the image is less
    assert outline[:, 1].min() == pytest.approx(tip[1] - tail[1], rel=0.02)   # drawn to the tip
    assert outline[:, 1].max() < 5                # nothing drawn upwards from the GCP
    labels = label_points(ax, [[10.0, 10.0]], ["G01"])
    assert labels[0].get_path_effects()           # outlined: readable on dark and bright pixels
    assert figure_problems(figure) == []
    plt.close(figure)


@pytest.mark.parametrize("call, message", [
    (lambda: gcp.GCPSet(np.zeros((3, 2)), np.zeros((3, 2)), enabled=[1, np.nan, 0]), "True/False"),
])
def test_silent_wrong_answers_are_value_errors(call, message):
    with pytest.raises(ValueError, match=message):
        call()


# --- .points files ---

GOOD = "mapX,mapY,sourceX,sourceY,enable\n500000,7400000,10,-20,1\n500100,7400000,20,-20,1\n"


def test_byte_order_mark_and_flags(tmp_path):
    path = tmp_path / "bom.points"
    path.write_bytes(("\ufeff" + GOOD.replace(",1\n500100", ",FALSE\n500100")).encode())
    gcps = gcp.read_points(path)
    assert gcps.enabled.tolist() == [False, True]
    path.write_text(GOOD.replace(",1\n500100", ",no\n500100").replace("20,1\n", "20,Yes\n"))
    assert gcp.read_points(path).enabled.tolist() == [False, True]
    path.write_text(GOOD.replace(",1\n500100", ",maybe\n500100"))
    with pytest.raises(gcp.DataError, match="line 2: enable must be 1 or 0.*'maybe'"):
        gcp.read_points(path)


def test_header_only_binary_and_package_data(tmp_path):
    path = tmp_path / "empty.points"
    path.write_text("mapX,mapY,sourceX,sourceY,enable\n")
    with pytest.raises(gcp.DataError, match="has a header but no points"):
        gcp.read_points(path)
    path.write_bytes(bytes(range(256)) * 4)
    with pytest.raises(gcp.DataError, match="not a text .points file"):
        gcp.read_points(path)
    import rsgeo

    gcps = gcp.GCPSet([[0, 0], [1, 0], [0, 1]], [[0, 0], [1, 0], [0, 1]])
    target = os.path.join(os.path.dirname(rsgeo.__file__), "data", "mine.points")
    with pytest.raises(gcp.DataError, match="data folder"):
        gcp.write_points(target, gcps)
    assert not os.path.exists(target)


def test_multiline_wkt_ids_and_notes_round_trip(tmp_path):
    from rasterio.crs import CRS

    wkt = CRS.from_epsg(31983).to_wkt().replace(",", ",\n    ")      # multi-line WKT
    assert "\n" in wkt
    gcps = gcp.GCPSet([[500000, 7400000], [500100, 7400000], [500000, 7400100]],
                      [[10, 20], [20, 20], [10, 10]], ids=["A", "B", "C"], crs=wkt,
                      notes=["road, crossing", "", "field corner"], enabled=[True, False, True])
    path = tmp_path / "wkt.points"
    gcp.write_points(path, gcps)
    again = gcp.read_points(path)
    assert path.read_text().splitlines()[1].startswith("mapX,mapY,sourceX,sourceY,enable")
    assert CRS.from_user_input(again.crs) == CRS.from_epsg(31983)
    assert again.ids == ["A", "B", "C"] and again.notes == gcps.notes
    assert again.enabled.tolist() == [True, False, True]


def test_gcpset_copies_the_arrays():
    map_xy = np.array([[0.0, 0], [100, 0], [0, 100]])
    gcps = gcp.GCPSet(map_xy, map_xy / 10)
    map_xy += 203
    assert gcps.map_xy[0].tolist() == [0.0, 0.0]
    with pytest.raises(TypeError, match="complex"):
        gcp.GCPSet(map_xy.astype(complex), map_xy)


def test_empty_ids_commas_quotes_and_unicode_separators_round_trip(tmp_path):
    # an id column keeps what it holds; U+2028, NEL and form feed are not line breaks in a .points
    # file (QGIS reads it line by line at \n or \r\n), although str.splitlines splits at them
    gcps = gcp.GCPSet([[0, 0], [1, 0], [0, 1]], [[0, 0], [1, 0], [0, 1]],
                      ids=["", "a,b", "x\u2028y"], notes=['say "q"', "", " \x85\x0c "])
    path = tmp_path / "texts.points"
    gcp.write_points(path, gcps)
    again = gcp.read_points(path)
    assert again.ids == ["", "a,b", "x\u2028y"]
    assert again.notes == ['say "q"', "", " \x85\x0c "]
    # QGIS's files have no id column: their GCPs are numbered
    path.write_text(GOOD)
    assert gcp.read_points(path).ids == ["1", "2"]


@pytest.mark.parametrize("ids, notes, message", [
    (["1", "2\n"], None, r"ids\[1\] is '2\\n', which holds a line break"),
    (None, ["", "a\rb"], r"notes\[1\] is 'a\\rb', which holds a line break"),
    (None, ["\0", ""], r"notes\[0\] .* NUL"),
])
def test_line_breaks_in_ids_and_notes_are_refused(tmp_path, ids, notes, message):
    # QgsGCPList::loadGcps reads one GCP per line and calls a short line malformed
    gcps = gcp.GCPSet([[0, 0], [1, 0]], [[0, 0], [1, 0]], ids=ids, notes=notes)
    path = tmp_path / "broken.points"
    with pytest.raises(gcp.GCPError, match=message):
        gcp.write_points(path, gcps)
    assert not path.exists()


def test_no_gcps_and_a_missing_folder_are_refused(tmp_path):
    # read_points refuses a header-only file, so write_points does not write one
    with pytest.raises(gcp.GCPError, match="holds no GCP.*at least one"):
        gcp.write_points(tmp_path / "none.points", gcp.GCPSet(np.empty((0, 2)), np.empty((0, 2))))
    assert not (tmp_path / "none.points").exists()
    gcps = gcp.GCPSet([[0, 0], [1, 0]], [[0, 0], [1, 0]])
    with pytest.raises(gcp.DataError, match=r"folder .* does not exist .*nowhere.*mkdir"):
        gcp.write_points(tmp_path / "nowhere" / "g.points", gcps)


def test_a_file_cut_short_mid_line_is_refused_with_the_file_and_the_line(tmp_path):
    # a writer killed (or a copy interrupted) mid-line left a last line without all its fields,
    # whose last number may be cut too: "-20.25" read as "-20.2" is a wrong GCP, not an error
    gcps = gcp.GCPSet([[500000, 7400000], [500100, 7400000], [500000, 7400100]],
                      [[10, 20.25], [20, 20], [10, 10]], crs="EPSG:31983")
    whole = tmp_path / "whole.points"
    gcp.write_points(whole, gcps)
    text = whole.read_text()
    last = text.rindex("\n", 0, -1) + 1                     # where line 5 (the third GCP) begins
    assert text.count("\n") == 5 and text[last:].count(",") == 9
    cut = tmp_path / "cut.points"
    # every cut that leaves the last line short of a field: before its ninth comma
    for end in range(last + 1, text.rindex(",") + 1):
        cut.write_text(text[:end])
        with pytest.raises(gcp.DataError, match=r"cut\.points, line 5: the line has \d of the "
                                                r"header's 10 fields \(.*note missing\)"):
            gcp.read_points(cut)
    # cut after the last comma only the empty note and the line break are gone: nothing is lost
    cut.write_text(text[:-1])
    assert np.array_equal(gcp.read_points(cut).image_xy, gcps.image_xy)


def test_a_short_line_in_a_qgis_file_is_refused_and_lines_are_counted_in_the_file(tmp_path):
    path = tmp_path / "qgis.points"
    path.write_text("#CRS: EPSG:31983\n"
                    "mapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n"
                    "\n"
                    "330000.5,7390000.25,10.5,-20.25,1,0.1,-0.2,0.22\n"
                    "331000,7389000,110,-120,0,0\n"
                    "332000,7391000,210,-20,1,0,0,0\n")
    with pytest.raises(gcp.DataError, match=r"qgis\.points, line 5: the line has 6 of the "
                                            r"header's 8 fields \(dY, residual missing\)"):
        gcp.read_points(path)
    # the same numbering for the other refusals: the #CRS line and blank lines count
    path.write_text("#CRS: EPSG:31983\nmapX,mapY,sourceX,sourceY,enable\n\n"
                    "500000,7400000,10,-20,maybe\n")
    with pytest.raises(gcp.DataError, match="line 4: enable must be 1 or 0"):
        gcp.read_points(path)


def test_write_points_refuses_a_model_of_the_wrong_shape(tmp_path):
    # a (n,) or (1, 2) answer broadcast against the GCPs into residuals that meant nothing
    gcps = data.load_gcps("cbers2b_ccd_hrc")
    model = gcps.fit(1)
    for wrong in (lambda points: model(points)[:, 0], lambda points: model(points)[:1]):
        with pytest.raises(gcp.GCPError, match=r"model returned shape \((14,|1, 2)\) for the "
                                               r"14 GCPs' .*shape \(14, 2\).*gcps\.fit"):
            gcp.write_points(tmp_path / "g.points", gcps, wrong)
    assert not (tmp_path / "g.points").exists()
    gcp.write_points(tmp_path / "g.points", gcps, model)
    assert len(gcp.read_points(tmp_path / "g.points")) == 14


def test_read_points_names_the_header_a_file_needs(tmp_path):
    """Both of QGIS's header sets named, and the missing columns of the one the file started."""
    path = tmp_path / "table.points"
    path.write_text("a,b,c\n1,2,3\n")
    with pytest.raises(ValueError, match=r"lacks \['mapX', 'mapY', 'sourceX', 'sourceY'\]; "
                                         r".*sourceX,sourceY,enable .*pixelX,pixelY,enable"):
        gcp.read_points(path)
    path.write_text("mapX,mapY,pixelX\n1,2,3\n")
    with pytest.raises(ValueError, match=r"lacks \['pixelY'\]"):
        gcp.read_points(path)
