"""Physics: BRDF models, microfacet distributions, Fresnel reflectance and direction geometry.

Nothing here integrates over the hemisphere; models are pure functions of directions and parameters.
"""
