"""The SVG plots: well-formed XML whatever the labels, long series thinned without losing spikes."""
import unittest
import xml.etree.ElementTree as ET

from swlio_report import svg_map, svg_plot


class Svg(unittest.TestCase):
    def test_time_plot_is_well_formed_with_odd_labels(self):
        svg = svg_plot.time_plot(
            [{"label": 'a <b> & "c"', "points": [(0, 1), (1, None), (2, 3)]}],
            "t<i>tle",
            "ms",
            events=[(1.0, "x < y & z", "failed")],
        )
        root = ET.fromstring(svg)
        self.assertEqual(root.tag, "svg")
        self.assertIn("t&lt;i&gt;tle", svg)

    def test_empty_and_constant_series(self):
        ET.fromstring(svg_plot.time_plot([{"label": "zero", "points": [(0, 0), (5, 0)]}], "z", "n"))
        ET.fromstring(svg_plot.time_plot([{"label": "one", "points": [(3, 7)]}], "o", "n"))

    def test_long_series_keep_their_spike(self):
        pts = [(i * 0.1, float(i % 5)) for i in range(50000)]
        pts[31234] = (3123.4, 99.0)
        thin = svg_plot.decimate(pts)
        self.assertLessEqual(len(thin), svg_plot.MAX_POINTS + 2)
        self.assertIn((3123.4, 99.0), thin)
        self.assertEqual(thin, sorted(thin))

    def test_top_view_is_well_formed(self):
        svg = svg_map.top_view(
            [{"label": "path", "points": [(0, 0), (10, 5), (20, 0)]}],
            [(1.0, 1.0), (2.0, -3.0)],
            [(10, 5, "14:32:07 lidar_silent & co", "failed")],
            "top",
        )
        ET.fromstring(svg)
        self.assertIn("lidar_silent &amp; co", svg)


if __name__ == "__main__":
    unittest.main()
