"""Reading Talus's particle layers (GeoPackage point layers, docs/outputs.md) with sqlite3 only."""
import sqlite3
import struct


def read_particle_layer(gpkg, columns):
    """[(x, y, *columns)] of every particle of a Talus particle layer: positions from the point
    geometry (GeoPackage binary header, then WKB), the named attribute columns as stored."""
    con = sqlite3.connect(str(gpkg))
    table = con.execute("SELECT table_name FROM gpkg_contents WHERE data_type='features'").fetchone()[0]
    geom = con.execute("SELECT column_name FROM gpkg_geometry_columns WHERE table_name=?", (table,)).fetchone()[0]
    names = ", ".join(f'"{c}"' for c in columns)
    rows = con.execute(f'SELECT "{geom}", {names} FROM "{table}"').fetchall()
    con.close()
    out = []
    for blob, *values in rows:
        env = [0, 32, 48, 48, 64][(blob[3] >> 1) & 7]  # envelope size from the header's flags
        wkb = blob[8 + env:]
        x, y = struct.unpack(("<" if wkb[0] == 1 else ">") + "dd", wkb[5:21])
        out.append((x, y, *values))
    return out
