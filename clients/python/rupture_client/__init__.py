"""Python client for rupture-server: submit sweeps, wait for them, and read their results as pandas
DataFrames.

    from rupture_client import Client
    c = Client("http://127.0.0.1:8080")            # token="..." when the server has one
    job = c.submit("dynamic-tension", inputs, {"loading.strain_rate": [1e5, 1e6]}, name="rates", reuse=True)
    c.wait(job, progress=True)                        # a progress bar on stderr
    table = c.summary(job)                            # a DataFrame; units in table.attrs["units"]

Every error the server answers with raises RuptureError carrying its status, its problem document
and the server's message (detail).
"""
from .client import Client, RuptureError

__all__ = ["Client", "RuptureError", "__version__"]
__version__ = "0.1.0"
