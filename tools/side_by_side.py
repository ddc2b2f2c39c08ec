#!/usr/bin/env python3
"""Pictures of two batch runs side by side, the README's before/after of the best view.

    tools/side_by_side.py OUT.png BEFORE_DIR AFTER_DIR NAME...

Each NAME's NAME_view.png (meshsal batch --view) from BEFORE_DIR, then from AFTER_DIR, in
one row; two such pairs per row of OUT.png. Needs numpy; reads and writes 8-bit PNGs itself.
"""
import zlib, struct, numpy as np, sys
def read_png(p):
    d=open(p,'rb').read(); assert d[:8]==b'\x89PNG\r\n\x1a\n'
    i=8; idat=b''; w=h=ct=None
    while i<len(d):
        n=struct.unpack('>I',d[i:i+4])[0]; t=d[i+4:i+8]; c=d[i+8:i+8+n]; i+=12+n
        if t==b'IHDR': w,h,bd,ct=struct.unpack('>IIBB',c[:10]); assert bd==8
        elif t==b'IDAT': idat+=c
    ch={2:3,6:4,0:1}[ct]; raw=zlib.decompress(idat); stride=w*ch
    out=np.zeros((h,stride),np.uint8); prev=np.zeros(stride,np.int32)
    for y in range(h):
        f=raw[y*(stride+1)]; line=np.frombuffer(raw[y*(stride+1)+1:(y+1)*(stride+1)],np.uint8).astype(np.int32)
        cur=np.zeros(stride,np.int32)
        if f==0: cur=line
        elif f==2: cur=(line+prev)&255
        else:
            for x in range(stride):
                a=cur[x-ch] if x>=ch else 0; b=prev[x]; c=prev[x-ch] if x>=ch else 0
                if f==1: v=a
                elif f==3: v=(a+b)//2
                else:
                    pa,pb,pc=abs(b-c),abs(a-c),abs(a+b-2*c)
                    v=a if pa<=pb and pa<=pc else (b if pb<=pc else c)
                cur[x]=(line[x]+v)&255
        out[y]=cur; prev=cur
    img=out.reshape(h,w,ch)
    if ch==4: img=img[:,:,:3]
    if ch==1: img=np.repeat(img,3,2)
    return img
def write_png(p,img):
    h,w,_=img.shape; raw=b''.join(b'\x00'+img[y].tobytes() for y in range(h))
    def chunk(t,c): return struct.pack('>I',len(c))+t+c+struct.pack('>I',zlib.crc32(t+c)&0xffffffff)
    open(p,'wb').write(b'\x89PNG\r\n\x1a\n'+chunk(b'IHDR',struct.pack('>IIBBBBB',w,h,8,2,0,0,0))+chunk(b'IDAT',zlib.compress(raw,9))+chunk(b'IEND',b''))
before_dir, after_dir, names = sys.argv[2], sys.argv[3], sys.argv[4:]
rows=[]
for n in names:
    a=read_png(f'{before_dir}/{n}_view.png'); b=read_png(f'{after_dir}/{n}_view.png')
    H=max(a.shape[0],b.shape[0])
    pad=lambda x: np.concatenate([x,np.full((H-x.shape[0],x.shape[1],3),255,np.uint8)]) if x.shape[0]<H else x
    gap=np.full((H,16,3),255,np.uint8)
    rows.append(np.concatenate([pad(a),gap,pad(b)],1))
W=max(r.shape[1] for r in rows)
rows=[np.concatenate([r,np.full((r.shape[0],W-r.shape[1],3),255,np.uint8)],1) for r in rows]
# two pairs per row of the sheet
out=[]
for i in range(0,len(rows),2):
    pair=rows[i:i+2]
    if len(pair)==1: pair.append(np.full_like(pair[0],255))
    H=max(p.shape[0] for p in pair)
    pair=[np.concatenate([p,np.full((H-p.shape[0],p.shape[1],3),255,np.uint8)]) for p in pair]
    out.append(np.concatenate([pair[0],np.full((H,40,3),255,np.uint8),pair[1]],1))
write_png(sys.argv[1],np.concatenate(out,0))
