"""Surface texture: roughness parameters of each surface and Seq of each pair (sec. 2.3.4)."""
