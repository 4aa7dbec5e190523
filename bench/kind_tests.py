# bench/kind_tests.py - per material kind (and the total-Lagrangian solver), the functions of
# sphsolid.h's implementation that test it (its enum value, or the model flag standing for it),
# with the chapter each sits in: the figure of issue 36 ("functions outside its chapter and the
# generic switch that test its kind"). A rough grep: comments are skipped, a function is the
# last definition line seen. Usage: python3 bench/kind_tests.py [sphsolid.h]
import re,sys
src=open(sys.argv[1] if len(sys.argv) > 1 else 'sphsolid.h').read().split('\n')
start=next(i for i,l in enumerate(src) if l.startswith('#ifdef SPHSOLID_IMPLEMENTATION'))
pats={
 'elastic':[r'SPS_MATERIAL_ELASTIC\b'],
 'rigid':[r'SPS_MATERIAL_RIGID\b',r'->kinematic\b',r'\.kinematic\b'],
 'J2':[r'SPS_MATERIAL_J2\b',r'SPS__YIELD_VON_MISES\b',r'SPS__LAW_J2\b'],
 'fluid':[r'SPS_MATERIAL_FLUID\b',r'SPS__VISCOUS_NEWTON\b',r'material->shear\b'],
 'Saint Venant-Kirchhoff':[r'SPS_MATERIAL_SAINT_VENANT_KIRCHHOFF\b',r'SPS__LAW_SAINT_VENANT_KIRCHHOFF\b'],
 'Neo-Hookean':[r'SPS_MATERIAL_NEO_HOOKEAN\b',r'SPS__LAW_NEO_HOOKEAN\b'],
 'Drucker-Prager':[r'SPS_MATERIAL_DRUCKER_PRAGER\b',r'SPS__YIELD_DRUCKER_PRAGER\b',r'\bmirrored\b'],
 'total Lagrangian (solver)':[r'SPS_SOLVER_TOTAL_LAGRANGIAN\b',r'total_lagrangian\b'],
}
func=None; chapter=None
res={k:{} for k in pats}
fre=re.compile(r'^(?:static |SPSDEF |SPS__INLINE )[^;=]*?\b(sps_?_?\w+)\(')
for i in range(start,len(src)):
    l=src[i]
    m=re.match(r'^/\* >>(.*?)(\*/|$)',l)
    if m: chapter=m.group(1).strip()
    m=fre.match(l)
    if m and not l.rstrip().endswith(';'): func=m.group(1)
    elif l.startswith('}'): func='(file scope)'
    code=l.split('/*')[0]
    for k,ps in pats.items():
        if any(re.search(p,code) for p in ps):
            res[k].setdefault(func,chapter)
for k,v in res.items():
    v.pop('(file scope)',None)
    print('%-26s %2d functions: %s'%(k,len(v),', '.join('%s [%s]'%(f,(c or '')[:24]) for f,c in v.items())))
