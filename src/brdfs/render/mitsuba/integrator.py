"""``brdfs_path``: a unidirectional path tracer for Mitsuba 3 written in Python, one bounce at a time.

Per camera ray the estimator is the usual one of pbrt-v4's ``PathIntegrator`` and Mitsuba's
``path`` plugin (Veach 1997, ch. 9):

* at every surface vertex, **next-event estimation** of *every* light (:func:`scene_lights`: the
  spherical area lights and point lights, not the sky): one direction from each light's own
  ``sample_direction``, a shadow ray, and the contribution ``β f cos / p_light`` weighted by the
  power heuristic ``w_light = p_light² / (p_light² + p_bsdf²)`` (a delta emitter has ``p_bsdf = 0``).
  Sampling every light instead of one chosen at random removes the noise of that choice (Fig. 3.9's
  p95 of the relative standard error fell from 0.147 to 0.082 at 64 spp, for 1.4× the time);
  the sky is left to BSDF sampling (:func:`scene_lights`);
* the path continues by **BSDF sampling** (the plugin's ``sample``: the model's own strategy, and
  one-sample MIS over a material's lobes inside the plugin); where the sampled ray meets an emitter
  (or leaves the scene into the sky), its radiance is added with ``w_bsdf = p_bsdf² / (p_bsdf² +
  p_light²)``, ``p_light`` that light's own density (the sky's weight is 1);
* **caustics** (property ``caustics``, default True): with False, a light is neither sampled nor
  counted when met at a vertex that has only glossy lobes (a metal) after a diffuse bounce, so
  the paths diffuse → metal → light (the caustics a metal throws on a diffuse floor, the fireflies
  of a unidirectional tracer) are dropped; reflections in the metals (eye → metal → … → light) and
  the sky the metals reflect stay. Measured at 64 spp (``benchmarks/render_preview_noise.py
  --set renders.caustics=1``): dropping them darkens the gray floors by 1.1-2.1 % (Figs. 3.9, 4.9),
  a metal reflecting such a floor by up to 2.8 % (3.9's tank), the metal spheres by 0.5-0.7 %, the
  plastics not at all; Fig. 3.9's p95 of the relative standard error falls from 0.070 to 0.049 and
  its time by 18 %;
* **clamping** (property ``clamp``, default 0: off; issue 42's caustic treatment): every contribution
  of light that arrives after the first scattering event (next-event estimation and emitters met by
  BSDF sampling from the second vertex on: indirect light, the paths rough metal → near-mirror →
  light of Fig. 3.11) is scaled down so that its largest channel (over all colour groups, so its
  hue is kept) is at most ``clamp``; the light it loses goes to the AOVs ``k<g>_<channel>`` (one
  per colour group, after the ``c<g>_*``), so the bias of the clamp is measured in the same render
  (it is exactly minus the mean of those AOVs) and direct light is never clamped;
* **colour groups** (property ``colour_groups``, default 1): with G > 1 a path carries G throughputs,
  one per group of three wavelengths (:mod:`brdfs.render.mitsuba.spectral`); the samplers do not
  read the colour, so group g's throughput is group 0's times f_g / f_0 at every vertex (the
  plugins' ``colour_ratios``, 1 for a gray material, :func:`colour_ratios`), the emitters are white,
  and groups 1 … G − 1 leave in the AOVs ``c<g>_<channel>`` after ``cos_v``;
* **Russian roulette** from depth ``rr_depth`` on: a path survives with probability
  ``q = min(0.95, max β)`` (the largest channel of every colour group) and its throughput is
  divided by q (unbiased; this is *not* the 0/1 accept/reject sampling that section 4.2.4 of the
  thesis calls Russian roulette);
  ``max_depth = -1`` means no fixed limit. (Starting it at depth 2 or 1 instead of 4 saved no time
  on Fig. 3.9's scene and raised its p95 from 0.070 to 0.087 and 0.109.)

The bounce loop is a Python ``while`` loop that ``@dr.syntax`` turns into ``dr.while_loop``: with
Dr.Jit's default flags it is traced once into one kernel (fast); inside :func:`wavefront` (symbolic
calls and loops switched off) it runs one evaluated iteration at a time, so that a BSDF implemented
in numpy (the generic plugin ``brdfs_model``) can read its arguments. The integrator writes the AOVs
``id``, the index + 1 of the BSDF of the shape the camera ray hits first (:func:`scene_bsdfs`; 0 for the
background), the object ID buffer of :mod:`brdfs.render.mitsuba.metrics`; ``cos_v``, cos θ_V
at that hit (0 for the background), for the material editor's S·a(θ_V) of Figure 3.8; and, last,
``id_sq``, the square of ``id``: a pixel's mean ``id`` is an object's only where the variance
mean(id²) − mean(id)² is 0 (half the samples on object 3 and half on object 5 average to 4).

The lines marked ``# MUTATION:<name>`` are the switches of ``make check-mutations``
(``workflow/scripts/check_mutations.sh`` rewrites each in a temporary copy and expects a named
test to fail).
"""
from __future__ import annotations

import contextlib
import functools

import drjit as dr
import mitsuba as mi

NAME = "brdfs_path"
#: The depth limit of max_depth = -1 (never reached: Russian roulette ends the paths).
UNLIMITED = 1 << 30
#: Largest survival probability of Russian roulette (paths never live forever).
RR_MAX_SURVIVAL = 0.95


@contextlib.contextmanager
def wavefront(enabled: bool = True):
    """Inside the ``with`` block (where ``enabled``), Dr.Jit evaluates calls and loops one kernel at a
    time, so that a numpy BSDF (the generic plugin ``brdfs_model``) can read its inputs; afterwards its
    flags are as they were (symbolic by default: one traced kernel, fast)."""
    flags = {flag: dr.flag(flag) for flag in (dr.JitFlag.SymbolicCalls, dr.JitFlag.SymbolicLoops)}
    try:
        for flag, value in flags.items():
            dr.set_flag(flag, value and not enabled)
        yield
    finally:
        for flag, value in flags.items():
            dr.set_flag(flag, value)


def power_heuristic(pdf_a, pdf_b):
    """Veach's power heuristic (β = 2), pdf_a² / (pdf_a² + pdf_b²); 0 where both vanish."""
    a2, b2 = dr.square(pdf_a), dr.square(pdf_b)
    return dr.select(a2 > 0, dr.detach(a2 / (a2 + b2)), 0.0)


def scene_bsdfs(scene) -> list:
    """The scene's distinct BSDFs in the order of first appearance in ``scene.shapes()``.

    The ``id`` AOV numbers BSDFs, not shapes: Mitsuba merges meshes that share a BSDF, and an
    object of several parts (a tank, a bust) is one material, one ID.
    """
    out = []
    for shape in scene.shapes():
        bsdf = shape.bsdf()
        if all(bsdf is not seen for seen in out):
            out.append(bsdf)
    return out


def scene_lights(scene) -> list:
    """The emitters that next-event estimation samples: every one but the infinite ones (the sky).

    A constant sky is reached by BSDF sampling alone: the plugins' samplers follow f cos, so under a
    constant sky their estimate is exact up to visibility, while a sky sample (uniform over the
    sphere, half of it below the horizon) and the uniform choice of one emitter out of all only add
    variance.
    """
    return [e for e in scene.emitters() if not mi.has_flag(e.flags(), mi.EmitterFlags.Infinite)]


def _glossy_only(bsdf):
    """True where the BSDF has a glossy lobe and no diffuse one (a metal, not a plastic)."""
    flags = bsdf.flags()
    return mi.has_flag(flags, mi.BSDFFlags.Glossy) & ~mi.has_flag(flags, mi.BSDFFlags.Diffuse)


def object_index(scene, si):
    """1-based index (as a Float) of the hit shape's BSDF in :func:`scene_bsdfs`; 0 where the ray escaped."""
    ids = mi.Float(0.0)
    hit_bsdf = si.bsdf()
    for k, bsdf in enumerate(scene_bsdfs(scene)):
        ids = dr.select(si.is_valid() & (hit_bsdf == mi.BSDFPtr(bsdf)), float(k + 1), ids)
    return ids


@functools.lru_cache(maxsize=None)
def integrator_class(variant: str):
    """The ``brdfs_path`` class for ``variant`` (Mitsuba's base classes exist per variant)."""
    if mi.variant() != variant:
        raise ValueError(f"integrator_class({variant!r}): Mitsuba's variant is {mi.variant()!r}")
    return type("BrdfsPath", (mi.SamplingIntegrator,), {k: v for k, v in vars(_BrdfsPathMethods).items()
                                                          if k not in ("__dict__", "__weakref__")})


class _BrdfsPathMethods:
    """Path tracer with NEE, power-heuristic MIS and Russian roulette (module docstring).

    Properties: ``max_depth`` (int, default -1: unlimited, paths end by Russian roulette; else the
    number of scattering events, 1 = direct lighting), ``rr_depth`` (int, default 4: the first depth
    at which Russian roulette may end a path), ``hide_emitters`` (bool, default False: camera rays
    that miss see ``background`` instead of the sky or a light), ``background`` (float, default 0) and
    ``count_rays`` (bool, default False: count camera, shadow and continuation rays in ``rays``),
    ``caustics`` (bool, default True: False drops the paths diffuse → metal → light, module docstring),
    ``clamp`` (float, default 0: off; else the largest channel of an indirect contribution, module docstring),
    ``colour_groups`` (int, default 1: the throughputs a path carries, module docstring) and
    ``passes`` (int, default 1: with P > 1, AOVs ``p<k>_<c>`` carry each sample's radiance in the
    AOV of its pass k = P·(i mod spp)/spp, i the sample's lane; see :func:`pass_index`).
    """

    def __init__(self, props):
        mi.SamplingIntegrator.__init__(self, props)
        self.max_depth = int(props.get("max_depth", -1))
        self.rr_depth = int(props.get("rr_depth", 4))
        self.hide_emitters = bool(props.get("hide_emitters", False))
        self.background = float(props.get("background", 0.0))
        self.count_rays = bool(props.get("count_rays", False))
        self.passes = int(props.get("passes", 1))
        self.caustics = bool(props.get("caustics", True))
        self.colour_groups = int(props.get("colour_groups", 1))
        self.clamp = float(props.get("clamp", 0.0))
        if not self.clamp >= 0.0:
            raise ValueError(f"brdfs_path: clamp = {self.clamp}: must be >= 0 (0: off)")
        if self.passes < 1:
            raise ValueError(f"brdfs_path: passes = {self.passes}: must be >= 1")
        if self.colour_groups < 1 or (self.colour_groups > 1 and self.passes > 1):
            raise ValueError(f"brdfs_path: colour_groups = {self.colour_groups}: must be >= 1, and 1 with passes > 1")
        self.rays = dr.zeros(mi.UInt32, 1)          # rays cast so far (count_rays), cumulative
        if self.max_depth < -1 or self.max_depth == 0:
            raise ValueError(f"brdfs_path: max_depth = {self.max_depth}: must be -1 (unlimited) or >= 1")
        if self.background < 0 or (self.background > 0 and not self.hide_emitters):
            raise ValueError(f"brdfs_path: background = {self.background}: needs hide_emitters and >= 0")
        if self.rr_depth < 1:
            raise ValueError(f"brdfs_path: rr_depth = {self.rr_depth}: must be >= 1")
        self.bounce_limit = UNLIMITED if self.max_depth == -1 else self.max_depth
        self.bounce_limit = self.bounce_limit  # MUTATION:depth3 self.bounce_limit = min(self.bounce_limit, 3)

    def aov_names(self):
        return (["id", "cos_v"] + colour_group_aov_names(self.colour_groups) + clamp_aov_names(self.colour_groups, self.clamp)
                + pass_aov_names(self.passes) + ["id_sq"])

    def _count(self, active):
        if self.count_rays:
            dr.scatter_reduce(dr.ReduceOp.Add, self.rays, mi.UInt32(1), mi.UInt32(0), active)

    @dr.syntax
    def sample(self, scene, sampler, ray, medium=None, active=True):
        bsdf_ctx = mi.BSDFContext()
        ray = mi.Ray3f(ray)
        active = mi.Bool(active)

        # The camera ray: the object ID, what it sees of emitters, the background where it misses.
        si = scene.ray_intersect(ray, ray_flags=mi.RayFlags.All, coherent=True, active=active)
        self._count(active)
        object_id = object_index(scene, si)
        cos_v = dr.select(si.is_valid(), dr.abs(si.wi.z), 0.0)
        seen = active & (si.is_valid() | mi.Bool(not self.hide_emitters))
        L = dr.select(seen, si.emitter(scene, seen).eval(si, seen), 0.0)
        L = dr.select(active & ~si.is_valid() & mi.Bool(self.hide_emitters), L + self.background, L)
        # one radiance and throughput per colour group (the emitters are white: the same in every group)
        Ls = (L,) * self.colour_groups
        lost = (mi.Spectrum(0.0),) * self.colour_groups       # what the clamp took (clamp > 0)
        betas = (mi.Spectrum(1.0),) * self.colour_groups
        depth = mi.UInt32(0)
        after_diffuse = mi.Bool(False)
        active &= si.is_valid()
        lights = scene_lights(scene)

        while active:
            bsdf = si.bsdf(ray)

            # Next-event estimation at this vertex (scattering event number depth + 1): every light.
            nee = active & mi.has_flag(bsdf.flags(), mi.BSDFFlags.Smooth)
            nee &= mi.Bool(True)  # MUTATION:nee_first_vertex nee &= depth == 0
            caustic = after_diffuse & _glossy_only(bsdf) & mi.Bool(not self.caustics)
            nee &= ~caustic
            for emitter in lights:
                value, ratios = self._light_sample(scene, emitter, bsdf, bsdf_ctx, si, sampler, nee)
                Ls, lost = self._add(Ls, lost, nee, betas, value, ratios, depth)

            # BSDF sampling: the next direction, and what it meets.
            bs, bsdf_weight, ratios = self._bsdf_sample(bsdf, bsdf_ctx, si, sampler, active)
            betas = _scale_each(betas, active, bsdf_weight, ratios)
            prev_si = mi.Interaction3f(si)
            delta = mi.has_flag(bs.sampled_type, mi.BSDFFlags.Delta)
            after_diffuse |= mi.has_flag(bs.sampled_type, mi.BSDFFlags.Diffuse)
            ray = si.spawn_ray(si.to_world(bs.wo))
            active &= (bs.pdf > 0) & (_largest(betas) != 0.0)
            si = scene.ray_intersect(ray, ray_flags=mi.RayFlags.All, coherent=False, active=active)
            self._count(active)

            # The emitter (or the sky) the BSDF sample meets; a light's radiance MIS-weighted against
            # its own light sample (every light is sampled at every vertex), the sky's with weight 1.
            emitter = si.emitter(scene, active)
            hit_emitter = active & (emitter != None)  # noqa: E711  (Dr.Jit pointer comparison)
            hit_light = hit_emitter & si.is_valid() & ~delta
            hit_emitter &= ~(caustic & si.is_valid())
            ds = mi.DirectionSample3f(scene, si=si, ref=prev_si)
            em_pdf = emitter.pdf_direction(prev_si, ds, hit_light)
            w_bsdf = dr.select(hit_light, power_heuristic(bs.pdf, em_pdf), 1.0)
            radiance = w_bsdf * emitter.eval(si, hit_emitter)
            Ls, lost = self._add(Ls, lost, hit_emitter, betas, radiance, _ONE * len(betas), depth)

            depth[active] += 1
            active &= si.is_valid() & (depth < self.bounce_limit)

            # Russian roulette, weight 1/q.
            q = dr.minimum(_largest(betas), RR_MAX_SURVIVAL)
            roulette = active & (depth >= self.rr_depth)
            survive = sampler.next_1d(roulette) < q
            betas = _scale_each(betas, roulette, 1.0 / dr.maximum(q, 1e-30), _ONE * len(betas))
            active &= ~roulette | survive
        lost_aovs = [channel for Lg in lost for channel in _channels(Lg)] if self.clamp > 0 else []
        return (Ls[0], mi.Bool(True), [object_id, cos_v] + _group_channels(Ls) + lost_aovs
                + self._pass_aovs(sampler, Ls[0]) + [dr.square(object_id)])

    def _add(self, Ls, lost, mask, betas, value, ratios, depth):
        """L_g + β_g · value · r_g per colour group where ``mask``; with ``clamp`` > 0 a contribution at
        ``depth`` ≥ 1 (indirect light) is scaled so that its largest channel over the groups is at most
        ``clamp``, and what it loses is added to ``lost``."""
        if self.clamp <= 0:
            return _add_each(Ls, mask, betas, value, ratios), lost
        terms = [beta * value * r for beta, r in zip(betas, ratios)]
        largest = dr.max(terms[0])
        for term in terms[1:]:
            largest = dr.maximum(largest, dr.max(term))
        keep = dr.select((depth >= 1) & (largest > self.clamp), self.clamp / largest, 1.0)  # MUTATION:clamp_direct keep = dr.select(largest > self.clamp, self.clamp / largest, 1.0)
        Ls = tuple(dr.select(mask, Lg + keep * t, Lg) for Lg, t in zip(Ls, terms))
        lost = tuple(dr.select(mask, Kg + (1.0 - keep) * t, Kg) for Kg, t in zip(lost, terms))  # MUTATION:clamp_half_kept lost = tuple(dr.select(mask, Kg + 0.5 * (1.0 - keep) * t, Kg) for Kg, t in zip(lost, terms))
        return Ls, lost

    def _bsdf_sample(self, bsdf, bsdf_ctx, si, sampler, active):
        """``bsdf.sample`` and the colour ratios f_g / f_0 at the sampled direction (one call per vertex)."""
        sample1, sample2 = sampler.next_1d(active), sampler.next_2d(active)
        if self.colour_groups == 1:
            return (*bsdf.sample(bsdf_ctx, si, sample1, sample2, active), _ONE)
        groups = self.colour_groups

        def target(self_, ctx, si, sample1, sample2, active):
            bs, weight = self_.sample(ctx, si, sample1, sample2, active)
            return bs, weight, colour_ratios(self_, si, bs.wo, active, groups)
        return dr.dispatch(bsdf, target, bsdf_ctx, si, sample1, sample2, active)

    def _bsdf_eval_pdf(self, bsdf, bsdf_ctx, si, wo, active):
        """``bsdf.eval_pdf`` and the colour ratios f_g / f_0 at ``wo``."""
        if self.colour_groups == 1:
            return (*bsdf.eval_pdf(bsdf_ctx, si, wo, active), _ONE)
        groups = self.colour_groups

        def target(self_, ctx, si, wo, active):
            f, pdf = self_.eval_pdf(ctx, si, wo, active)
            return f, pdf, colour_ratios(self_, si, wo, active, groups)
        return dr.dispatch(bsdf, target, bsdf_ctx, si, wo, active)

    def _light_sample(self, scene, emitter, bsdf, bsdf_ctx, si, sampler, active):
        """β-free NEE term of one light: f cos L_e / p_light × w_light, zero where the shadow ray is
        blocked, and the colour ratios at the light's direction."""
        ds, em_weight = emitter.sample_direction(si, sampler.next_2d(active), active)
        active = active & (ds.pdf != 0.0)         # a new mask: Dr.Jit's &= would change the caller's
        visibility = True  # MUTATION:no_shadow_rays visibility = False
        if visibility:
            active = active & ~scene.ray_test(si.spawn_ray_to(ds.p), active)
            self._count(active)
        f_em, pdf_bsdf_em, ratios = self._bsdf_eval_pdf(bsdf, bsdf_ctx, si, si.to_local(ds.d), active)
        w_light = dr.select(ds.delta, 1.0, power_heuristic(ds.pdf, pdf_bsdf_em))
        return dr.select(active, w_light * f_em * em_weight, 0.0), ratios

    def _pass_aovs(self, sampler, L) -> list:
        """Per pass k and colour channel, L where the sample belongs to pass k, else 0."""
        if self.passes == 1:
            return []
        k = pass_index(dr.width(L), sampler.sample_count(), self.passes)
        return [dr.select(k == p, channel, 0.0) for p in range(self.passes) for channel in _channels(L)]


#: The colour ratios of a single colour group.
_ONE = (1.0,)


def _add_each(Ls, mask, betas, value, ratios) -> tuple:
    """L_g + β_g · value · r_g per colour group, where ``mask``."""
    return tuple(dr.select(mask, Lg + beta * value * r, Lg) for Lg, beta, r in zip(Ls, betas, ratios))


def _scale_each(betas, mask, factor, ratios) -> tuple:
    """β_g · factor · r_g per colour group, where ``mask``."""
    return tuple(dr.select(mask, beta * factor * r, beta) for beta, r in zip(betas, ratios))


def _group_channels(Ls) -> list:
    """The channels of colour groups 1 … G − 1 (the AOVs ``c<g>_*``)."""
    return [channel for Lg in Ls[1:] for channel in _channels(Lg)]


def _largest(betas):
    """The largest channel of any colour group's throughput (Russian roulette's survival)."""
    out = dr.max(betas[0])
    for beta in betas[1:]:
        out = dr.maximum(out, dr.max(beta))
    return out


def colour_ratios(bsdf, si, wo, active, groups: int) -> tuple:
    """(1, f_1 / f_0, …) of ``bsdf`` at (``si.wi``, ``wo``): its ``colour_ratios`` where it has
    colour groups, else 1 (a gray material: the scene builder gives a material that differs between
    groups its groups' parameters)."""
    own = getattr(bsdf, "colour_ratios", None)
    ratios = list(own(si, wo, active)) if own is not None else []
    if not ratios:
        ratios = [mi.Spectrum(1.0)] * (groups - 1)
    if len(ratios) != groups - 1:
        raise ValueError(f"brdfs_path: colour_groups = {groups}, but {bsdf} has {len(ratios) + 1}")
    return (mi.Spectrum(1.0), *ratios)


def colour_group_aov_names(groups: int) -> list[str]:
    """AOV names of the radiance of colour groups 1 … G − 1: ``c<g>_<channel>`` (group 0 is the image)."""
    channels = "RGB" if mi.is_rgb else "Y"
    return [f"c{g}_{c}" for g in range(1, groups) for c in channels]


def clamp_aov_names(groups: int, clamp: float) -> list[str]:
    """AOV names of the light the clamp took, per colour group: ``k<g>_<channel>`` (none without a clamp)."""
    if clamp <= 0:
        return []
    channels = "RGB" if mi.is_rgb else "Y"
    return [f"k{g}_{c}" for g in range(groups) for c in channels]


def pass_index(lanes: int, spp: int, passes: int):
    """The pass (0 … passes − 1) of each of ``lanes`` samples of one ``mi.render`` launch.

    Mitsuba's ``SamplingIntegrator.render`` (one wavefront, ``samples_per_pass`` unset) gives lane i
    to pixel i // spp, so i mod spp numbers the pixel's samples; each sample has its own random
    stream, and the spp samples of a pixel split into ``passes`` independent passes of spp / passes.
    """
    if spp % passes:
        raise ValueError(f"brdfs_path: spp = {spp} is not a multiple of passes = {passes}")
    return (dr.arange(mi.UInt32, lanes) % spp) // (spp // passes)


def _channels(L) -> tuple:
    if mi.is_rgb:
        return (L[0], L[1], L[2])
    if mi.is_monochromatic:
        return (L[0],)
    raise ValueError(f"brdfs_path: passes > 1 needs an rgb or mono variant, not {mi.variant()!r}")


def pass_aov_names(passes: int) -> list[str]:
    """AOV names of the per-pass radiance: ``p<k>_<channel>`` (none for one pass)."""
    if passes == 1:
        return []
    channels = "RGB" if mi.is_rgb else ("Y" if mi.is_monochromatic else "")
    return [f"p{p}_{c}" for p in range(passes) for c in channels]


def register() -> None:
    """Register ``brdfs_path`` with Mitsuba for the variant that is set."""
    cls = integrator_class(mi.variant())
    mi.register_integrator(NAME, lambda props: cls(props))
