"""A still of a recording for the offline site: the first useful frame of the recording's largest image stream,
decoded from the ``.rrd`` file (:mod:`tvtrack.pipeline.site` shows it beside the link that opens the viewer)."""

from __future__ import annotations

from pathlib import Path

__all__ = ["STILL_MIN_SIDE_PX", "recording_still"]

#: A still's shorter side is enlarged (nearest-neighbour pixels) to at least this many pixels.
STILL_MIN_SIDE_PX = 320


_CHANNEL_DTYPES = {
    6: "u1",
    7: "i1",
    8: "u2",
    9: "i2",
    10: "u4",
    11: "i4",
    12: "u8",
    13: "i8",
    33: "f2",
    34: "f4",
    35: "f8",
}  # rerun.datatypes.ChannelDatatype values
_CHANNELS = {1: 1, 2: 3, 3: 4}  # rerun.datatypes.ColorModel: L, RGB, RGBA


def _decode_images(batch):
    """Yield ``(frame, image)`` for each image row of a chunk's record batch (raw buffers or encoded blobs)."""
    import io

    import numpy as np
    from PIL import Image

    names = batch.schema.names
    frames = batch.column("frame").to_pylist() if "frame" in names else list(range(batch.num_rows))
    if "Image:buffer" in names:
        buffers, formats = batch.column("Image:buffer").to_pylist(), batch.column("Image:format").to_pylist()
        for k, (buf, fmt) in enumerate(zip(buffers, formats)):
            if not buf or not fmt or fmt[0].get("channel_datatype") not in _CHANNEL_DTYPES:
                continue
            f = fmt[0]
            channels = _CHANNELS.get(f.get("color_model") or 1)
            if channels is None:
                continue
            arr = np.frombuffer(bytes(buf[0]), dtype=_CHANNEL_DTYPES[f["channel_datatype"]])
            shape = (f["height"], f["width"]) + ((channels,) if channels > 1 else ())
            yield frames[k], arr.reshape(shape)
    elif "EncodedImage:blob" in names:
        for k, blob in enumerate(batch.column("EncodedImage:blob").to_pylist()):
            if blob:
                yield frames[k], np.asarray(Image.open(io.BytesIO(bytes(blob[0]))))


def recording_still(rrd: Path, out_png: Path) -> bool:
    """Save the first useful frame of the recording's largest image stream as a PNG.

    "Useful": the earliest frame whose image is not constant (searched in each image entity's first
    chunk that has one, so a long recording is not decoded whole). Images that are not 8-bit are stretched
    between their 0.5 and 99.5 percentiles (as the viewer's auto-range would); all are enlarged with nearest-neighbour
    pixels to at least :data:`STILL_MIN_SIDE_PX`. Returns ``False`` if the recording has no image.
    """
    import numpy as np
    from PIL import Image
    from rerun.chunk import RrdReader

    best = {}  # entity -> (frame, image): the earliest useful frame of the entity's first chunk holding one
    stream = RrdReader(rrd).stream().filter(components=["Image:buffer", "Image:format", "EncodedImage:blob"])
    for chunk in stream:
        if chunk.entity_path in best:
            continue  # chunks come in time order: later ones cannot hold an earlier frame worth decoding
        for frame, image in sorted(_decode_images(chunk.to_record_batch()), key=lambda fi: fi[0]):
            if np.ptp(image) > 0:
                best[chunk.entity_path] = (frame, image)
                break
    if not best:
        return False
    _, image = max(best.values(), key=lambda fi: fi[1].shape[0] * fi[1].shape[1])
    if image.dtype != np.uint8:
        lo, hi = np.percentile(image, [0.5, 99.5])
        image = np.clip((image.astype(float) - lo) / max(hi - lo, 1e-12) * 255, 0, 255).astype(np.uint8)
    scale = max(1, -(-STILL_MIN_SIDE_PX // min(image.shape[:2])))
    still = Image.fromarray(image.astype(np.uint8)).resize(
        (image.shape[1] * scale, image.shape[0] * scale), Image.NEAREST
    )
    out_png.parent.mkdir(parents=True, exist_ok=True)
    still.save(out_png)
    return True
