#!/usr/bin/env python3
# How the service request seeds of corpus/dds_messages were made (run by hand, not by CI):
#   python3 test/fuzz/request_seeds.py test/fuzz/corpus/dds_messages [NAN_MAJOR_OUT]
#   python3 test/fuzz/request_seeds.py test/fuzz/corpus/dds_messages --migrate  # a field added
# A plain-CDR (XCDR1) codec of rangefit_msgs/DetectRequest and of the service request
# (rangefit_msgs/srv/Detect request as rmw_cyclonedds frames it: U64 client writer id, I64
# sequence number, then the same fields). It first re-encodes every topic request seed
# (request_*, written by Cyclone's dds_stream_write) and prints whether the bytes come out the same
# (they do: the codec is Cyclone's layout), then writes the service_* seeds from them (first byte
# 4 selects the service request in the harness). With NAN_MAJOR_OUT it writes the two
# crash-*-nan-major-axis-accepted reproducers (a NaN bore_major_axis) there.
import struct, sys, os
V3 = ['d','d','d']
FIELDS = [('request_id','s'),('kind','s'),('model','s'),('bore_position',V3),('bore_axis',V3),
 ('bore_radius','d'),('sensor','s'),('sweep_start','d'),('sweep_end','d'),('sweep_speed','d'),
 ('bore_plane_normal',V3),('instances','I'),('hypotheses','I'),('trials','I'),('seed','Q'),
 ('bore_outer_radius','d'),('bore_walls','s'),('bore_normal_keep','d'),('view_dir',V3),
 ('sensor_position_given','?'),('sensor_position',V3),('parts','I'),('target','s'),
 ('target_edge','d'),('target_bar','d'),('target_pose',['d']*7),('bore_half_angle','d'),
 ('bore_cylinder_radius','d'),('bore_radius2','d'),('bore_major_axis',V3),('sensors','S'),
 ('target_radius','d'),('robot_pose_given','?'),('robot_pose',['d']*7),('calibration_scans','S'),
 ('target_tilt_given','?'),('target_tilt','d')]
# The fields added last, with the value --migrate gives them in a seed written before they existed
# (not given: no tilt and a zero one).
ADDED = {'target_tilt_given':False,'target_tilt':0.0}
HEADER = [('rmw_client_guid','Q'),('rmw_sequence_number','q')]
SIZE = {'d':8,'I':4,'Q':8,'q':8,'?':1}
class R:
  def __init__(s,b,e): s.b,s.p,s.e=b,0,e
  def al(s,n): s.p=(s.p+n-1)//n*n
  def prim(s,t):
    if t=='S':
      s.al(4); n,=struct.unpack_from(s.e+'I',s.b,s.p); s.p+=4; return [s.prim('s') for _ in range(n)]
    if t=='s':
      s.al(4); n,=struct.unpack_from(s.e+'I',s.b,s.p); s.p+=4; v=s.b[s.p:s.p+n-1]; s.p+=n; return v
    s.al(SIZE[t]); v,=struct.unpack_from(s.e+t,s.b,s.p); s.p+=SIZE[t]; return v
class W:
  def __init__(s,e): s.b=bytearray(); s.e=e
  def al(s,n):
    while len(s.b)%n: s.b.append(0)
  def prim(s,t,v):
    if t=='S':
      s.al(4); s.b+=struct.pack(s.e+'I',len(v))
      for x in v: s.prim('s',x)
      return
    if t=='s':
      s.al(4); s.b+=struct.pack(s.e+'I',len(v)+1)+v+b'\0'; return
    s.al(SIZE[t]); s.b+=struct.pack(s.e+t,v)
def read(fields,r):
  out={}
  for name,t in fields:
    out[name]=[r.prim(x) for x in t] if isinstance(t,list) else r.prim(t)
  return out
def write(fields,vals,w):
  for name,t in fields:
    if isinstance(t,list):
      for x,v in zip(t,vals[name]): w.prim(x,v)
    else: w.prim(t,vals[name])
def encode(fields,vals,little):
  w=W('<' if little else '>'); write(fields,vals,w)
  pad=(4-len(w.b)%4)%4; w.b+=b'\0'*pad
  return bytes([0,1 if little else 0,0,pad])+bytes(w.b)
def decode(fields,data):
  little=data[1]==1; r=R(data[4:],'<' if little else '>'); return read(fields,r),little
def migrate(corpus):
  # Seeds written before the fields of ADDED existed: the same fields, then ADDED's values. Run
  # once when fields are added (ADDED: those fields). It also writes, made from
  # request_calibrate, request_calibrate_css, a css calibration (sphere radius, robot pose, two
  # earlier scans), and request_calibrate_pantilt, a pantilt calibration (the cube's pose in the
  # head's world, the tilt given, one earlier sweep).
  old=[f for f in FIELDS if f[0] not in ADDED]
  for f in sorted(os.listdir(corpus)):
    b=open(os.path.join(corpus,f),'rb').read()
    if b[0]==1 and ('request' in f): head=[]
    elif b[0]==4 and ('service' in f): head=HEADER
    else: continue
    vals,little=decode(head+old,b[1:])
    vals.update({k:list(v) if isinstance(v,list) else v for k,v in ADDED.items()})
    open(os.path.join(corpus,f),'wb').write(b[:1]+encode(head+FIELDS,vals,little))
    print('migrated',f)
  def calibrate_seed(name,**changes):
    b=open(os.path.join(corpus,'request_calibrate'),'rb').read()
    vals,little=decode(FIELDS,b[1:])
    vals.update(changes)
    open(os.path.join(corpus,name),'wb').write(b'\x01'+encode(FIELDS,vals,little))
    print('wrote',name)
  calibrate_seed('request_calibrate_css',request_id=b'css-pose-3',target=b'css',
                 target_radius=0.0125,robot_pose_given=True,
                 robot_pose=[0.45,-0.1,0.6,0.0,0.7071067811865476,0.0,0.7071067811865476],
                 calibration_scans=[b'css-pose-1',b'css-pose-2'])
  # The cube 0.9 m before the head, turned 0.6 rad about z.
  calibrate_seed('request_calibrate_pantilt',request_id=b'sweep-2',target=b'pantilt',
                 target_pose=[0.9,-0.04,0.25,0.0,0.0,0.29552020666133955,0.955336489125606],
                 target_tilt_given=True,target_tilt=0.1,calibration_scans=[b'sweep-1'])
if __name__=='__main__' and len(sys.argv)>2 and sys.argv[2]=='--migrate':
  migrate(sys.argv[1]); sys.exit(0)
if __name__=='__main__':
  corpus=sys.argv[1]
  # Check: the topic seeds re-encode byte for byte (the codec is Cyclone's layout).
  for f in sorted(os.listdir(corpus)):
    if not f.startswith('request_'): continue
    b=open(os.path.join(corpus,f),'rb').read()
    vals,little=decode(FIELDS,b[1:])
    again=b'\x01'+encode(FIELDS,vals,little)
    print(f, 'round trip', 'ok' if again==b else 'DIFFERS (%d vs %d bytes)'%(len(again),len(b)))
  def service(src, out, guid, seq, **changes):
    b=open(os.path.join(corpus,src),'rb').read()
    vals,little=decode(FIELDS,b[1:])
    vals.update({k:v for k,v in changes.items() if k in vals})
    if 'target_w' in changes: vals['target_pose'][6]=changes['target_w']
    vals['rmw_client_guid']=guid; vals['rmw_sequence_number']=seq
    data=b'\x04'+encode(HEADER+FIELDS,vals,little)
    # The request header is 16 bytes, so the fields after it keep Cyclone's alignment: the
    # service sample is the topic sample with the header in front.
    if not changes:
      assert data[5:21]==struct.pack(('<' if little else '>')+'Qq',guid,seq) and data[21:]==b[5:], src
    open(os.path.join(corpus,out),'wb').write(data); print('wrote',out,len(data))
  service('request_bore_le','service_bore_le',0x0123456789abcdef,1)
  service('request_bore_be','service_bore_be',0x0123456789abcdef,2)
  service('request_object_linear','service_object_linear',0x01100f0000000001,3)
  service('request_hostile_id_wide_sweep','service_hostile_id_wide_sweep',0xffffffffffffffff,-1)
  service('request_bore_le','service_no_id',0x0110abcd00000003,42,request_id=b'')
  service('request_bore_be','service_no_id_be',0x0110abcd00000003,43,request_id=b'')
  service('request_object_linear','service_no_id_nan_orientation',0x0110abcd00000003,44,
          request_id=b'',target_w=float('nan'))
  if len(sys.argv) > 2:
    b=open(os.path.join(corpus,'request_bore_le'),'rb').read()
    vals,little=decode(FIELDS,b[1:])
    vals['bore_major_axis']=[float('nan'),0.0,0.0]
    open(sys.argv[2],'wb').write(b'\x01'+encode(FIELDS,vals,little))
    vals['rmw_client_guid']=5; vals['rmw_sequence_number']=6
    open(sys.argv[2]+'_service','wb').write(b'\x04'+encode(HEADER+FIELDS,vals,little))
