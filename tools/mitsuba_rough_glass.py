"""Mitsuba 3's reference for rough glass in the white furnace (src/render/path/tests.rs,
`rough_glass_in_the_furnace_matches_mitsuba`): a unit sphere of `roughdielectric` (GGX, visible
normals, η = 1.5) inside a constant environment of radiance 1, path traced to depth 64, the
mean of the centre 12 × 12 pixels of a 32 × 32 image. Run: python3 tools/mitsuba_rough_glass.py
(pip install mitsuba numpy)."""
import mitsuba as mi, numpy as np, sys
mi.set_variant('scalar_rgb')
res = {}
for alpha in [0.0025, 0.09, 0.36]:
    scene = mi.load_dict({
        'type': 'scene',
        'integrator': {'type': 'path', 'max_depth': 64, 'rr_depth': 1000},
        'sensor': {'type': 'perspective', 'fov': 40,
                   'to_world': mi.ScalarTransform4f().look_at(origin=[0,0,3.2], target=[0,0,0], up=[0,1,0]),
                   'film': {'type': 'hdrfilm', 'width': 32, 'height': 32, 'rfilter': {'type': 'box'}},
                   'sampler': {'type': 'independent', 'sample_count': 512}},
        'env': {'type': 'constant', 'radiance': {'type': 'rgb', 'value': [1,1,1]}},
        'ball': {'type': 'sphere', 'radius': 1.0,
                 'bsdf': {'type': 'roughdielectric', 'distribution': 'ggx', 'alpha': alpha, 'int_ior': 1.5, 'ext_ior': 1.0}},
    })
    img = np.array(mi.render(scene))
    c = img[10:22, 10:22, 0]   # the centre of the ball
    print(alpha, 'centre mean %.4f' % c.mean(), 'whole mean %.4f' % img[...,0].mean())
