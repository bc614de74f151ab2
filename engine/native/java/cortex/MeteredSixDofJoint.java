// Generated from org/engine.org by lein tangle: edit the chapter, not this file.
package cortex;

import com.jme3.bullet.joints.SixDofJoint;
import com.jme3.bullet.objects.PhysicsRigidBody;
import com.jme3.math.Matrix3f;
import com.jme3.math.Vector3f;

/** jME's SixDofJoint reporting its applied impulse (native Bullet writes it). */
public class MeteredSixDofJoint extends SixDofJoint {
    public MeteredSixDofJoint(PhysicsRigidBody nodeA, PhysicsRigidBody nodeB,
                              Vector3f pivotA, Vector3f pivotB,
                              Matrix3f rotA, Matrix3f rotB, boolean useLinearReferenceFrameA) {
        super(nodeA, nodeB, pivotA, pivotB, rotA, rotB, useLinearReferenceFrameA);
        setFeedback(true);
    }

    /** Native Bullet clamps and breaks the constraint itself at `threshold`. */
    public void setBreakingThreshold(float threshold) {
        setBreakingImpulseThreshold(threshold);
    }
}
