"""The measured files a joint generator wrote for one data set, every one the diagnosis reads."""

from pathlib import Path


def measured_files(data) -> list[Path]:
    """Bore profiles, maximum depths and, where the generator wrote them, the slider-acceleration
    and joint-force traces of ``data`` (a generator's ``DataSet``)."""
    traces = (data.acceleration_csv, data.force_csv)  # None where not written
    return [data.profiles_csv, data.max_wear_csv] + [path for path in traces if path]
