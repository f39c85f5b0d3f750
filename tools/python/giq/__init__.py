"""giq: how far real-time global illumination is from the path-traced truth.

The same C++ code as the giq command line, with numpy arrays in and out (docs/python.md).
"""


class Layers(dict):
    """An image's layers by name ('beauty', 'indirect', 'variance', 'objectId'...) as numpy arrays,
    with the EXR header's strings (.metadata) and each RGB layer's channel names (.channels)."""

    def __init__(self, layers=(), metadata=None, channels=None):
        super().__init__(layers)
        self.metadata = dict(metadata or {})
        self.channels = dict(channels or {})


from ._giq import *  # noqa: E402,F401,F403
from ._giq import __version__  # noqa: E402,F401
