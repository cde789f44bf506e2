"""Structures: polyhedral blocks, the interfaces between them and the supports (``docs/conventions.md``).

``geometry`` polyhedra and polygons (exact volumes and centroids) · ``assembly`` blocks,
interfaces, supports · ``contacts`` interface detection and overlap checks · ``io`` block
files (tce JSON, OBJ, COMPAS, with their stored interfaces) · ``arch`` (one ring or several),
``bridge``, ``vault``, ``dome`` generators · ``backing`` behind an arch's haunches · ``defects`` what an inspection finds, applied to an
assembly · ``params`` argument checks shared by the generators.
"""
