"""The check both install tests (check_wheel.py, check_pip_install.py) run in the installed
module's interpreter: `comic` imports from where it was installed, at the built version, and
detects features on a synthetic square."""


def installed_comic_check(prefix, version, label):
    """Python source asserting that `comic` comes from `prefix` at `version`; prints `label`."""
    return (
        "import comic, numpy\n"
        "assert comic.__file__.startswith(%r), comic.__file__\n"
        "assert comic.__version__ == %r, comic.__version__\n"
        "image = numpy.full((60, 60), 40, numpy.uint8)\n"
        "image[20:40, 20:40] = 200\n"
        "features, _ = comic.detect(image, detector='harris')\n"
        "assert len(features) >= 4, len(features)\n"
        "print(%r, comic.__file__, comic.__version__, len(features), 'features')\n"
    ) % (prefix, version, label)
