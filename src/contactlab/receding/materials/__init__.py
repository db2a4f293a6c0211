"""A layer and a half-plane of different materials: the sweep over Dundurs' beta
(``sweep``), its commands (``cli``) and report section (``report``). The kernels and
bilateral tractions are ``receding.core.bimaterial``, the materials ``core.materials``."""
