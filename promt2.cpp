#include <visp3/laser_conic/vpLaserConicSimulator.h>
#include "laser_sim_test_utils.h"
using namespace laser_sim_test;
typedef vpLaserConicSimulator::vpRenderSettings Settings;
int main(){
  Settings s; s.ambient=0.6; s.laserPower=150; s.distanceFalloff=2.0; s.lambertIncidence=true; s.stripeFarFraction=20.0/150; s.stripeWidth=3.0; s.noise=2.0; s.jpegQuality=90; s.floor=vpLaserConicSimulator::FLOOR_MOSAIC; s.reflectanceScaled=true;
  vpLaserConicSimulator sim=makeSimulator(vpHomogeneousMatrix(0.05,-0.03,1.0,vpMath::rad(30),vpMath::rad(-8),0.3),93);
  auto t=sim.traceTruth(6000,s); sim.measureProminence(t,s);
  for(auto q: {vpImagePoint(227,490),vpImagePoint(204,510),vpImagePoint(80,770),vpImagePoint(964,940)}){ size_t b=0; double bd=1e9; for(size_t k=0;k<t.size();++k){double d=vpImagePoint::distance(q,t[k].point); if(d<bd){bd=d;b=k;}}
    printf("(%.0f,%.0f) peak %.1f (%.1f s) prom %.1f (%.1f s)\n",t[b].point.get_u(),t[b].point.get_v(),t[b].peakDominance,t[b].peakOverNoise,t[b].prominence,t[b].prominenceOverNoise);}
}
