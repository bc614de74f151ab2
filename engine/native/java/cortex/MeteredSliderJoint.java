// Generated from org/engine.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.jme3.bullet.joints.SliderJoint;
import com.jme3.bullet.objects.PhysicsRigidBody;
import com.jme3.math.Matrix3f;
import com.jme3.math.Vector3f;

/** jME's SliderJoint reporting its applied impulse (native Bullet writes it). */
public class MeteredSliderJoint extends SliderJoint {
    public MeteredSliderJoint(PhysicsRigidBody nodeA, PhysicsRigidBody nodeB,
                              Vector3f pivotA, Vector3f pivotB,
                              Matrix3f rotA, Matrix3f rotB, boolean useLinearReferenceFrameA) {
        super(nodeA, nodeB, pivotA, pivotB, rotA, rotB, useLinearReferenceFrameA);
        setFeedback(true);
    }
}
